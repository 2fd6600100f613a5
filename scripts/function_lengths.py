#!/usr/bin/python3
"""Lengths of the C++ functions in the given folders, counted in lines.

A function's length runs from the first line of its signature to its closing
brace, both included. Functions are the bodies that open at namespace or class
scope after a parameter list; lambdas and local classes count towards the
function that holds them. Comments, strings and preprocessor lines are ignored
when braces are matched.

  scripts/function_lengths.py slam experiments            # summary
  scripts/function_lengths.py slam experiments --top 20   # the longest
  scripts/function_lengths.py experiments --max 60        # exit 1 above 60
"""
import argparse
import os
import re
import statistics
import sys

SCOPE_KEYWORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b")
CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|do|else|try)\b")


def strip_code(text):
    """Blanks comments, string and character literals, and preprocessor lines,
    keeping newlines so that line numbers stay right."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                i += 1
            continue
        if c == "/" and text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if c == "/" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append("\n" * text.count("\n", i, end))
            i = end
            continue
        if c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            if m:
                closing = ")" + m.group(1) + '"'
                end = text.find(closing, i + m.end())
                end = n if end < 0 else end + len(closing)
                out.append('""' + "\n" * text.count("\n", i, end))
                i = end
                continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        if c == "\n":
            at_line_start = True
        elif not c.isspace():
            at_line_start = False
        out.append(c)
        i += 1
    return "".join(out)


def functions(path):
    """Yields (name, first_line, length_lines) for each function in a file."""
    with open(path, encoding="utf-8", errors="replace") as handle:
        code = strip_code(handle.read())
    # Stack of scopes: True where the brace opened a namespace/class scope.
    scopes = []
    statement_start = 0
    i, n = 0, len(code)
    while i < n:
        c = code[i]
        if c in ";":
            statement_start = i + 1
        elif c == "{":
            head = code[statement_start:i]
            in_declarative_scope = all(scopes)
            if in_declarative_scope and is_member_brace_init(head):
                # "Foo::Foo(int a) : b_{a} {": the member's braces, then the body
                i = matching_brace(code, i) + 1
                continue
            declaration = without_template_heads(head)
            if (in_declarative_scope and ")" in declaration and not CONTROL.match(declaration)
                    and not SCOPE_KEYWORDS.search(declaration.split("(")[0])
                    and "=" not in declaration.split("(")[0]):
                end = matching_brace(code, i)
                signature = head.strip()
                first = code.count("\n", 0, statement_start + (len(head) - len(head.lstrip())))
                last = code.count("\n", 0, end)
                yield name_of(signature), first + 1, last - first + 1
                i = end + 1
                statement_start = i
                continue
            scopes.append(in_declarative_scope and bool(SCOPE_KEYWORDS.search(head))
                          or (in_declarative_scope and head.strip().startswith("extern")))
            statement_start = i + 1
        elif c == "}":
            if scopes:
                scopes.pop()
            statement_start = i + 1
        elif c == ":" and all(scopes):
            # access specifiers ("public:") end a declaration head
            word = code[statement_start:i].strip()
            if word in ("public", "private", "protected"):
                statement_start = i + 1
        i += 1


def without_template_heads(head):
    """The head without its "template <...>" parts, so that "template <class T>"
    is not read as a class."""
    out, i = [], 0
    for m in re.finditer(r"\btemplate\s*<", head):
        if m.start() < i:
            continue
        out.append(head[i:m.start()])
        depth, j = 0, m.end() - 1
        while j < len(head):
            depth += {"<": 1, ">": -1}.get(head[j], 0)
            j += 1
            if depth == 0:
                break
        i = j
    out.append(head[i:])
    return "".join(out)


def is_member_brace_init(head):
    """True for the head of a constructor's initializer list whose member is
    initialised with braces ("Foo(int a) : a_(a), b_" before "{a}")."""
    close = head.find(")")
    if close < 0:
        return False
    after_params = head[close + 1:]
    return bool(re.search(r"(?<!:):(?!:)", after_params)) and bool(re.search(r"\w\s*$", after_params))


def matching_brace(code, open_index):
    depth = 0
    for j in range(open_index, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def name_of(signature):
    before_params = signature.split("(")[0].split()
    return before_params[-1] if before_params else signature[:40]


def source_files(folders):
    for folder in folders:
        for root, _, names in os.walk(folder):
            for name in sorted(names):
                if name.endswith((".cc", ".h", ".cpp", ".hpp")):
                    yield os.path.join(root, name)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folders", nargs="+")
    parser.add_argument("--top", type=int, default=0, help="list the N longest functions")
    parser.add_argument("--max", type=int, default=0,
                        help="exit 1 and list every function longer than this")
    args = parser.parse_args()
    found = []
    for path in source_files(args.folders):
        for name, line, length in functions(path):
            found.append((length, f"{path}:{line}", name))
    if not found:
        print("no functions found", file=sys.stderr)
        return 1
    lengths = sorted(length for length, _, _ in found)
    p90 = lengths[min(len(lengths) - 1, int(0.9 * len(lengths)))]
    print(f"{len(lengths)} functions: median {statistics.median(lengths):g}, "
          f"p90 {p90}, max {lengths[-1]} lines")
    found.sort(reverse=True)
    for length, where, name in found[:args.top]:
        print(f"{length:5d}  {where}  {name}")
    if args.max:
        over = [f for f in found if f[0] > args.max]
        for length, where, name in over:
            print(f"over {args.max}: {length:5d}  {where}  {name}")
        return 1 if over else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
