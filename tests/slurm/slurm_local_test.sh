#!/usr/bin/env bash
# ctest slurm/LocalClusterUpDown (label slurm): scripts/slurm_local.sh
#   - a cluster that does not come up (its controller's port already taken)
#     is one line naming the daemon and the log to read, exit 1, and leaves no
#     daemon running;
#   - up brings an idle node, up again says so and keeps its slurm.conf (other
#     DUSKMAP_SLURM_PORTS), up again timing out stops nothing, down as a user
#     other than root is one line and stops nothing, down stops each daemon by
#     its PID, down again does nothing; no daemon is left.
# Exits 77 (ctest SKIP_RETURN_CODE) without Slurm and munge, or when not root.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
source "$repo/tests/slurm/cluster_test_setup.sh" duskmap_slurm_local_test
listener=""
cleanup() {
  local rc=$?
  [ -z "$listener" ] || kill "$listener" 2>/dev/null || true
  bash "$repo/scripts/slurm_local.sh" down "$state" >/dev/null || true
  if [ "${DUSKMAP_KEEP_TEST_TMP:-0}" = 1 ]; then echo "kept $tmp"; else rm -rf "$tmp"; fi
  exit $rc
}
trap cleanup EXIT
check() { echo "FAILED: $*" >&2; exit 1; }
daemons_of() {  # the live daemons whose command line names the state folder
  local pid
  for pid in $(pgrep -x 'munged|slurmctld|slurmd' || true); do
    grep -qF "$state" "/proc/$pid/cmdline" 2>/dev/null && echo "$pid"
  done
  return 0
}

# The controller's port taken: slurmctld exits, and up says so on one line.
export DUSKMAP_SLURM_PORTS="16927 16928" DUSKMAP_SLURM_UP_TIMEOUT_S=30
/usr/bin/python3 -c '
import socket, sys, time
s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(("0.0.0.0", 16927)); s.listen(); print("listening", flush=True); time.sleep(120)
' >"$tmp/listener.log" 2>&1 &
listener=$!
# SO_REUSEADDR: the port may still hold closed connections (TIME_WAIT) of a run
# just before; a second listener is refused all the same.
until grep -qs listening "$tmp/listener.log"; do
  kill -0 "$listener" 2>/dev/null || check "the listener on port 16927 did not start: $(cat "$tmp/listener.log")"
  sleep 0.1
done
if bash "$repo/scripts/slurm_local.sh" up "$state" >"$tmp/up.out" 2>"$tmp/up.err"; then
  check "up succeeded although its port is taken"
fi
[ "$(wc -l <"$tmp/up.err")" -eq 1 ] || check "not one line: $(cat "$tmp/up.err")"
grep -qF "the cluster did not come up: slurmctld exited" "$tmp/up.err" || check "$(cat "$tmp/up.err")"
grep -qF "read $state/log/slurmctld.log" "$tmp/up.err" || check "no log named: $(cat "$tmp/up.err")"
[ -z "$(daemons_of)" ] || check "daemons left running after a failed up: $(daemons_of)"
kill "$listener"
wait "$listener" 2>/dev/null || true
listener=""

bash "$repo/scripts/slurm_local.sh" up "$state" | tee "$tmp/up.out"
grep -q "cluster up: node .* idle" "$tmp/up.out" || check "up: $(cat "$tmp/up.out")"
[ "$(daemons_of | wc -l)" -eq 3 ] || check "not three daemons: $(daemons_of)"
conf_before=$(cat "$state/slurm.conf")
DUSKMAP_SLURM_PORTS="16937 16938" bash "$repo/scripts/slurm_local.sh" up "$state" >"$tmp/up2.out"
grep -q "cluster already up" "$tmp/up2.out" ||
  check "up twice"
[ "$(daemons_of | wc -l)" -eq 3 ] || check "up twice started more daemons"
[ "$(cat "$state/slurm.conf")" = "$conf_before" ] || check "up on a running cluster rewrote its slurm.conf"
# Up on a running cluster whose node is not idle in time fails but stops nothing.
if DUSKMAP_SLURM_UP_TIMEOUT_S=0 bash "$repo/scripts/slurm_local.sh" up "$state" 2>"$tmp/up.err"; then
  check "up with no time to wait succeeded"
fi
grep -qF "the cluster is up, but its node" "$tmp/up.err" || check "up timed out: $(cat "$tmp/up.err")"
[ "$(daemons_of | wc -l)" -eq 3 ] || check "a timed-out up stopped a cluster it did not start"
# Down needs root: as another user it is one line and stops nothing.
if runuser -u nobody -- bash "$repo/scripts/slurm_local.sh" down "$state" >"$tmp/down.out" 2>"$tmp/down.err"; then
  check "down as nobody succeeded"
fi
[ "$(wc -l <"$tmp/down.err")" -eq 1 ] && grep -qF "must run as root" "$tmp/down.err" ||
  check "down as nobody: $(cat "$tmp/down.err")"
[ ! -s "$tmp/down.out" ] || check "down as nobody printed: $(cat "$tmp/down.out")"
[ "$(daemons_of | wc -l)" -eq 3 ] || check "down as nobody stopped daemons"
SLURM_CONF="$state/slurm.conf" sinfo -h -o '%T' >"$tmp/sinfo.out"
grep -q idle "$tmp/sinfo.out" || check "sinfo does not see an idle node"
bash "$repo/scripts/slurm_local.sh" down "$state" | tee "$tmp/down.out"
[ "$(grep -c '^stopped ' "$tmp/down.out")" -eq 3 ] || check "down: $(cat "$tmp/down.out")"
[ -z "$(daemons_of)" ] || check "daemons left after down: $(daemons_of)"
bash "$repo/scripts/slurm_local.sh" down "$state" >"$tmp/down2.out"
grep -q "cluster not running" "$tmp/down2.out" || check "down twice"
echo PASSED
