# Sourced by the tests that run a local Slurm cluster (slurm_local_test.sh,
# slurm_matrix_test.sh): exits 77 (ctest SKIP_RETURN_CODE) with a message
# when Slurm or munge is not installed or the test is not run as root, and
# otherwise makes the test's folder ($tmp, reachable by the munge user) and
# names the cluster's state folder ($state) inside it.
#   source cluster_test_setup.sh NAME   (NAME: the folder's prefix)
missing=""
for program in munged slurmctld slurmd sbatch squeue sinfo scancel; do
  command -v "$program" >/dev/null || missing+=" $program"
done
if [ -n "$missing" ]; then
  echo "SKIPPED: Slurm is not installed (missing:$missing); scripts/setup.sh installs slurm-wlm and munge"
  exit 77
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIPPED: the local Slurm cluster needs root (slurmd runs jobs as their users)"
  exit 77
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/${1:?usage: source cluster_test_setup.sh NAME}.XXXXXX")
chmod 755 "$tmp"  # munged runs as the munge user and must reach its folder inside
state="$tmp/cluster"
