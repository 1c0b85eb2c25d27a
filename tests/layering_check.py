#!/usr/bin/env python3
"""The folders are the stages, and no stage reaches back (docs/architecture.md).

    python3 tests/layering_check.py SOURCE_ROOT

Checks, over every .h/.cpp file of the stage folders:
  * a file includes project headers only from its own folder or one before it
    in core < cad < topology < background < sizing < mesher < io < app (mesher/ops/ and
    app/python/ belong to their parent folder);
  * the mesher includes nothing from sizing/: it sees the size field of
    core/size_field.h alone;
  * only cad/ includes OpenCASCADE headers (*.hxx);
  * no file is over 400 lines (nor any of tests/ and bench/);
  * every stage folder has a README.md saying what it owns.
Prints each violation on one line and exits 1 if there is any.
"""
import os
import re
import sys

ORDER = ["core", "cad", "topology", "background", "sizing", "mesher", "io", "app"]
FORBIDDEN = {("mesher", "sizing")}  # (from, to) allowed by the order but not wanted
MAX_LINES = 400
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    problems = []
    files = 0
    for folder in ORDER:
        base = os.path.join(root, folder)
        if not os.path.isfile(os.path.join(base, "README.md")):
            problems.append(f"{folder}/: no README.md saying what it owns")
        for dirpath, _, names in os.walk(base):
            for name in sorted(names):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                files += 1
                with open(path, encoding="utf-8") as f:
                    lines = f.read().split("\n")
                count = len(lines) - (lines[-1] == "")
                if count > MAX_LINES:
                    problems.append(f"{rel}: {count} lines, over {MAX_LINES}")
                for n, line in enumerate(lines, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    kind, target = m.groups()
                    if kind == "<" and target.endswith(".hxx") and folder != "cad":
                        problems.append(f"{rel}:{n}: includes OpenCASCADE <{target}> outside cad/")
                    if kind == '"' and "/" in target:
                        to = target.split("/")[0]
                        if to not in ORDER:
                            continue  # tests/ helpers are not included by the stages; others are not ours
                        if ORDER.index(to) > ORDER.index(folder):
                            problems.append(f"{rel}:{n}: {folder}/ includes {target}, a later stage")
                        elif (folder, to) in FORBIDDEN:
                            problems.append(f"{rel}:{n}: {folder}/ includes {target}")
    for folder in ("tests", "bench"):
        base = os.path.join(root, folder)
        for name in sorted(os.listdir(base)):
            if name.endswith((".h", ".cpp")):
                files += 1
                with open(os.path.join(base, name), encoding="utf-8") as f:
                    n = len(f.read().rstrip("\n").split("\n"))
                if n > MAX_LINES:
                    problems.append(f"{folder}/{name}: {n} lines, over {MAX_LINES}")
    for p in problems:
        print(p)
    print(f"{files} files in {len(ORDER)} stage folders, tests/ and bench/, {len(problems)} problems")
    return 1 if problems or files == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
