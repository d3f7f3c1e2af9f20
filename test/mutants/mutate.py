#!/usr/bin/env python3
"""Mutation testing by hand-written mutants (docs/testing.md, "Mutants").

Each mutant in mutants.py replaces one exact piece of text of the library by
another. This script copies the repository (working tree and _build, not .git)
to a scratch directory, and for each mutant: applies it there, builds the test
runner, runs the suites the mutant names, records which test cases failed, and
puts the file back. The repository itself is never changed.

usage: python3 test/mutants/mutate.py [--copy DIR] [--json FILE] [ID ...]
  run from the repository root; no ID: every mutant. DIR defaults to
  /tmp/raytrace-mutants (refreshed with rsync each run).
"""
import argparse, json, os, re, subprocess, sys, time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
ap = argparse.ArgumentParser()
ap.add_argument("--copy", default="/tmp/raytrace-mutants")
ap.add_argument("--json")
ap.add_argument("ids", nargs="*")
args = ap.parse_args()
spec = {}
exec(open(os.path.join(here, "mutants.py")).read(), spec)
everything = spec["MUTANTS"] + spec.get("PROBES", [])
mutants = spec["MUTANTS"] if not args.ids else [m for m in everything if m["id"] in args.ids]
unknown = set(args.ids) - {m["id"] for m in everything}
if unknown:
    sys.exit("no such mutant: " + " ".join(sorted(unknown)))

# Every mutant's text must occur exactly once in its file, checked in the
# repository before anything runs: a mutant whose text has moved (a split,
# a rename) stops the run, rather than being skipped and counted as nothing.
def enclosing(src, at):
    """Module.function around offset [at]: the last top-level [let] that
    starts before the end of its line."""
    end = src.find("\n", at)
    name = "?"
    for mo in re.finditer(r"^(?:let|and)(?:\[@[^\]]*\])?(?: rec)?\s+([a-z_][A-Za-z0-9_']*)", src[: end if end >= 0 else len(src)], re.M):
        name = mo.group(1)
    return name

stale, where = [], {}
for m in mutants:
    path = os.path.join(root, m["file"])
    src = open(path).read() if os.path.exists(path) else None
    n = -1 if src is None else src.count(m["old"])
    if n != 1:
        stale.append(f"{m['id']}: {m['file']}: " + ("no such file" if n < 0 else f"the text to replace occurs {n} times"))
    else:
        at = src.index(m["old"])
        module = os.path.splitext(os.path.basename(m["file"]))[0].capitalize()
        where[m["id"]] = (src[:at].count("\n") + 1, f"{module}.{enclosing(src, at)}")
if stale:
    sys.exit("mutants whose text is not found exactly once (update test/mutants/mutants.py):\n  " + "\n  ".join(stale))

copy = args.copy
os.makedirs(copy, exist_ok=True)
subprocess.run(["rsync", "-a", "--delete", "--exclude", ".git", root + "/", copy + "/"], check=True)

def build():
    r = subprocess.run("dune build @install test/test.exe 2>&1 | head -20", shell=True, cwd=copy, capture_output=True, text=True)
    return r.stdout.strip()

err = build()
if err:
    sys.exit("the unmutated copy does not build:\n" + err)
test_dir = os.path.join(copy, "_build/default/test")
env = dict(os.environ, RAYTRACE_EXE=os.path.join(copy, "_build/default/bin/main.exe"),
           RAYTRACE_EXAMPLE=os.path.join(copy, "_build/default/examples/hello_scene.exe"))
results = []
for m in mutants:
    path = os.path.join(copy, m["file"])
    src = open(path).read()
    line, function = where[m["id"]]
    open(path, "w").write(src.replace(m["old"], m["new"]))
    try:
        err = build()
        if err:
            print(f"{m['id']} {m['file']}:{line} does not build:\n{err}", flush=True)
            results.append({"id": m["id"], "file": m["file"], "function": function, "status": "no build"})
            continue
        failed, t0 = set(), time.time()
        for suite in m["suites"]:
            r = subprocess.run(["timeout", "900", "./test.exe", "test"] + suite.split(), cwd=test_dir, env=env,
                               capture_output=True, text=True)
            out = r.stdout + r.stderr
            cases = {f"{a} {b}" for a, b in re.findall(r"\[FAIL\]\s+(\S+)\s+(\d+)\s", out)}
            failed |= cases
            if r.returncode != 0 and not cases:
                failed.add(f"{suite}: exit {r.returncode}")
        status = "caught" if failed else "survived"
        print(f"{m['id']} {m['file']}:{line} ({function}) [{status}] by {', '.join(sorted(failed)) or '-'}"
              f" ({time.time() - t0:.0f} s; suites {'; '.join(m['suites'])})", flush=True)
        results.append({"id": m["id"], "file": m["file"], "line": line, "function": function, "status": status, "failed": sorted(failed)})
    finally:
        open(path, "w").write(src)
if args.json:
    json.dump(results, open(args.json, "w"), indent=1)
# A mutant that does not build tests nothing: the run fails, naming it.
broken = [r["id"] for r in results if r["status"] == "no build"]
if broken:
    sys.exit("mutants that do not build (rewrite them in test/mutants/mutants.py): " + " ".join(broken))
