#!/usr/bin/env python3
"""Mutation testing of repose: plant one realistic bug at a time in src/, rebuild, run the suite, and report
which test killed each mutant or that none did. See docs/testing.md; operators in operators.py.

The work happens in a copy of the source tree (BUILD/tree) with its own build directory (BUILD/build), so the
working tree is never modified and can be edited while a run goes on. Results are appended to
BUILD/results.jsonl as they come, so a stopped run resumes where it was; the Markdown table is written at the
end (and with --report alone).

A survivor is then run against the pinned hash of the engine's output (60 drops of 8 shapes, both
integrators, every bit of every result): "same results" means the mutant changed no bit of them, the
evidence for classifying it as equivalent in what it computes (a cost, a bound that is never tight, a
guide whose answer is verified); "results change" means a test is missing.

A mutant whose object file is byte-identical to the original's is equivalent by construction (trivial
compiler equivalence) and is not tested. A mutant that does not compile is "stillborn" and not counted. A
test that runs longer than max(60 s, 5 x its time on the unmutated code) kills the mutant ("timeout"):
mutation testing counts a hang as a detected bug, and the suite's own time bounds would catch it too.
"""

import argparse
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mutants import mutants_of, sampled  # noqa: E402
from report import load_equivalents, module_of, write_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
# Never run: the pinned hash of the engine's output fails on any change, right or wrong; the package tests
# install and build a consumer (minutes, and they test packaging, not results).
PINNED_HASH = "Determinism.FixedBatchHashesToTheGoldenValue"
DEFAULT_EXCLUDE = r"^Determinism\.FixedBatchHashesToTheGoldenValue$|^package\."


# ---- the copy of the tree and its build -------------------------------------------------------------------


def tree_files(commit):
    """{relative path: bytes} of the source tree: the working tree's tracked and untracked (not ignored)
    files, or those of a commit."""
    if commit:
        names = subprocess.run(["git", "ls-tree", "-r", "-z", "--name-only", commit], cwd=ROOT,
                               capture_output=True, check=True).stdout.decode().split("\0")
        return {n: subprocess.run(["git", "show", f"{commit}:{n}"], cwd=ROOT, capture_output=True,
                                  check=True).stdout for n in filter(None, names)}
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT,
                            capture_output=True, check=True).stdout.decode().split("\0")
    return {n: (ROOT / n).read_bytes() for n in filter(None, listed) if (ROOT / n).is_file()}


def sync_tree(tree, commit):
    """Makes `tree` hold the source files (see tree_files), writing only those that differ so that the
    incremental build stays incremental. When the tree moves to another commit every file is touched, so the
    next build is a whole one: an incremental build across commits once kept a stale object (session 14)."""
    files = tree_files(commit)
    stamp = tree.parent / "tree.commit"
    moved = not stamp.exists() or stamp.read_text() != str(commit)
    for rel, data in files.items():
        dst = tree / rel
        if dst.is_file() and dst.read_bytes() == data:
            if moved:
                os.utime(dst)
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_bytes(data)
        if rel.endswith((".sh", ".py")):
            dst.chmod(0o755)
    stamp.write_text(str(commit))


def build(build_dir, log):
    with open(log, "w") as out:
        return subprocess.run(["cmake", "--build", str(build_dir), "-j", str(os.cpu_count() or 2)],
                              stdout=out, stderr=subprocess.STDOUT).returncode == 0


def object_file(build_dir, rel_path):
    """The object file CMake makes of src/DIR/FILE.cpp for the library target."""
    rel = Path(rel_path).relative_to("src")
    for target in ("repose.dir", "repose_mpi.dir"):
        candidate = build_dir / "src" / "CMakeFiles" / target / (str(rel) + ".o")
        if candidate.exists():
            return candidate
    return None


def list_tests(build_dir, exclude):
    info = json.loads(subprocess.run(["ctest", "--show-only=json-v1"], cwd=build_dir, capture_output=True,
                                     check=True).stdout)
    tests = []
    for t in info["tests"]:
        if re.search(exclude, t["name"]) or "command" not in t:
            continue
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        env = dict(os.environ)
        for item in props.get("ENVIRONMENT", []):
            k, _, v = item.partition("=")
            env[k] = v
        tests.append({"name": t["name"], "command": t["command"],
                      "cwd": props.get("WORKING_DIRECTORY", str(build_dir)), "env": env,
                      "setup": set(props.get("FIXTURES_SETUP", [])),
                      "requires": set(props.get("FIXTURES_REQUIRED", []))})
    return tests


def results_same(build_dir):
    """Whether the pinned hash of the engine's output (PINNED_HASH) still holds: the mutant changed no bit of
    the results of that batch."""
    [test] = [t for t in list_tests(build_dir, r"(?!)") if t["name"] == PINNED_HASH]
    return subprocess.run(test["command"], cwd=test["cwd"], env=test["env"], stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, timeout=600).returncode == 0


def run_tests(tests, order, timeouts, jobs, stop_on_failure=True):
    """Runs the tests in `order`, `jobs` at a time. Returns (first failing test or None, how it failed,
    {name: seconds})."""
    pending, running, durations = list(order), {}, {}
    failed, how = None, None
    while (pending and not (failed and stop_on_failure)) or running:
        while pending and len(running) < jobs and not (failed and stop_on_failure):
            # CTest's fixtures: a test waits until every test that sets up what it requires has ended (the
            # Fortran example reads the reference another test writes).
            unset = {f for n in pending + list(running) for f in tests[n].get("setup", ())}
            ready = [n for n in pending if not (tests[n].get("requires", set()) & unset)]
            if not ready:
                break
            name = ready[0]
            pending.remove(name)
            t = tests[name]
            proc = subprocess.Popen(t["command"], cwd=t["cwd"], env=t["env"], stdout=subprocess.DEVNULL,
                                    stderr=subprocess.DEVNULL, start_new_session=True)
            running[name] = (proc, time.monotonic())
        time.sleep(0.01)
        for name, (proc, start) in list(running.items()):
            elapsed = time.monotonic() - start
            rc = proc.poll()
            timed_out = rc is None and elapsed > timeouts.get(name, 1e9)
            if rc is None and not timed_out and not (failed and stop_on_failure):
                continue
            if rc is None:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
            del running[name]
            if rc is None and not timed_out:
                continue  # stopped because another test already failed
            durations[name] = elapsed
            if (timed_out or rc != 0) and failed is None:
                failed, how = name, "timeout" if timed_out else "failed"
    return failed, how, durations


# ---- main -------------------------------------------------------------------------------------------------


def source_files(paths):
    files = []
    for p in paths:
        full = (ROOT / p).resolve()
        if full.is_dir():
            files += sorted(str(f.relative_to(ROOT)) for f in full.rglob("*.cpp"))
        elif full.is_file():
            files.append(str(full.relative_to(ROOT)))
        else:
            sys.exit(f"mutate: {p}: no such file or directory")
    for f in files:
        if not f.startswith("src/"):
            sys.exit(f"mutate: {f}: only files under src/ are mutated")
    return files


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="*", default=["src/sim", "src/geometry", "src/model", "src/poses"],
                    help="files or directories under src/ (default: the physics modules)")
    ap.add_argument("--sample", type=float, default=1.0, help="fraction of the mutants to run (default 1)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the sample")
    ap.add_argument("--build", default=str(ROOT / "build" / "mutate"), help="work directory")
    ap.add_argument("--exclude", default=DEFAULT_EXCLUDE, help="regex of test names never run")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="tests run at once")
    ap.add_argument("--list", action="store_true", help="list the mutants and stop")
    ap.add_argument("--report", action="store_true", help="only write the report from the results so far")
    ap.add_argument("--fresh", action="store_true", help="forget earlier results")
    ap.add_argument("--retest", default="",
                    help="comma-separated outcomes to run again (e.g. survived,timeout after adding tests)")
    ap.add_argument("--check-survivors", action="store_true",
                    help="run the pinned hash on every survivor that has not had it (results_same)")
    ap.add_argument("--out", default=None, help="Markdown table (default BUILD/report.md)")
    ap.add_argument("--commit", default=None, help="mutate this commit's tree (default: the working tree)")
    args = ap.parse_args()

    sources = tree_files(args.commit)
    if args.commit:  # that commit's files under the paths (they may differ from the working tree's)
        prefixes = [p.rstrip("/") for p in args.paths]
        files = sorted(f for f in sources if f.startswith("src/") and f.endswith(".cpp") and
                       any(f == p or f.startswith(p + "/") for p in prefixes))
    else:
        files = source_files(args.paths)
    mutants = [m for f in files for m in mutants_of(f, sources[f].decode()) if sampled(m, args.sample, args.seed)]
    command = "scripts/mutate.sh " + " ".join(
        ([f"--sample {args.sample} --seed {args.seed}"] if args.sample < 1 else []) + args.paths)
    if args.list:
        for m in mutants:
            print(f"{m['key']} {m['file']}:{m['line']} {m['operator']}: {m['mutated']}")
        print(f"{len(mutants)} mutants", file=sys.stderr)
        return 0

    work = Path(args.build)
    tree, build_dir = work / "tree", work / "build"
    results_path = work / "results.jsonl"
    report_path = Path(args.out) if args.out else work / "report.md"
    work.mkdir(parents=True, exist_ok=True)
    if args.fresh and results_path.exists():
        results_path.unlink()
    done = {}
    if results_path.exists():
        for line in results_path.read_text().splitlines():
            r = json.loads(line)
            done[r["key"]] = r
    wanted = {m["key"] for m in mutants}
    retest = set(filter(None, args.retest.split(",")))
    if retest:  # only this run's mutants; survivors already shown equivalent stay as they are
        equivalents = load_equivalents()
        done = {k: r for k, r in done.items()
                if k not in wanted or r["outcome"] not in retest or k in equivalents}
    if args.report:
        write_report([r for k, r in done.items() if k in wanted], report_path, command)
        print(f"report: {report_path}")
        return 0

    print(f"mutate: {len(mutants)} mutants in {len(files)} files ({len(wanted & done.keys())} done before)")
    sync_tree(tree, args.commit)
    # Checked containers: an index one past the end is then a crash, as in CI's sanitizer build.
    subprocess.run(["cmake", "-S", str(tree), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                    "-DREPOSE_BUILD_BENCH=OFF", "-DREPOSE_CHECKED_STL=ON"], check=True, stdout=subprocess.DEVNULL)
    if not build(build_dir, work / "build.log"):
        sys.exit(f"mutate: the unmutated tree does not build; see {work / 'build.log'}")

    tests = {t["name"]: t for t in list_tests(build_dir, args.exclude)}
    baseline_path = work / "baseline.json"
    baseline = json.loads(baseline_path.read_text()) if baseline_path.exists() else {}
    if set(baseline.get("durations", {})) != set(tests) or baseline.get("tree") != tree_digest(tree, files):
        print(f"mutate: baseline run of {len(tests)} tests")
        failed, how, durations = run_tests(tests, sorted(tests), {}, args.jobs, stop_on_failure=False)
        if failed:
            sys.exit(f"mutate: the unmutated suite fails ({failed} {how}); fix it first")
        baseline = {"durations": durations, "tree": tree_digest(tree, files)}
        baseline_path.write_text(json.dumps(baseline))
    durations = baseline["durations"]
    timeouts = {n: max(60.0, 5 * d) for n, d in durations.items()}
    kills = {}  # tests that killed mutants go first: most mutants die to a handful of tests
    for r in done.values():
        if r.get("killer"):
            kills[r["killer"]] = kills.get(r["killer"], 0) + 1

    originals = {f: (tree / f).read_text() for f in files}
    objects = {}
    for f in files:
        obj = object_file(build_dir, f)
        objects[f] = obj.read_bytes() if obj else None
    if retest:  # the file keeps the last outcome of every mutant
        results_path.write_text("".join(json.dumps(r) + "\n" for r in done.values()))
    results_file = open(results_path, "a")

    def plant(m):  # one bug at a time: the mutated line in the tree's copy of its file
        lines = originals[m["file"]].split("\n")
        lines[m["line"] - 1] = m["text"]
        (tree / m["file"]).write_text("\n".join(lines))

    def keep(record):
        results_file.write(json.dumps(record) + "\n")
        results_file.flush()
        done[record["key"]] = record

    try:
        for i, m in enumerate(mutants):
            if args.check_survivors:  # the pinned hash of the survivors so far, nothing else
                if m["key"] not in done or done[m["key"]]["outcome"] != "survived" or \
                        "results_same" in done[m["key"]]:
                    continue
                plant(m)
                record = dict(done[m["key"]])
                record["results_same"] = build(build_dir, work / "mutant-build.log") and results_same(build_dir)
                (tree / m["file"]).write_text(originals[m["file"]])
                keep(record)
                print(f"[{i + 1}/{len(mutants)}] {m['file']}:{m['line']} {m['operator']}: pinned batch "
                      f"{'same results' if record['results_same'] else 'results change'}", flush=True)
                continue
            if m["key"] in done:
                continue
            plant(m)
            t0 = time.monotonic()
            record = {k: m[k] for k in ("key", "file", "line", "operator", "original", "mutated")}
            if not build(build_dir, work / "mutant-build.log"):
                record["outcome"] = "stillborn"
            else:
                obj = object_file(build_dir, m["file"])
                if obj and objects[m["file"]] is not None and obj.read_bytes() == objects[m["file"]]:
                    record["outcome"] = "same-object"
                else:
                    order = sorted(tests, key=lambda n: (-kills.get(n, 0), durations.get(n, 0)))
                    killer, how, _ = run_tests(tests, order, timeouts, args.jobs)
                    record["outcome"] = "survived" if killer is None else ("timeout" if how == "timeout"
                                                                           else "killed")
                    if killer:
                        record["killer"] = killer
                        kills[killer] = kills.get(killer, 0) + 1
                    else:
                        record["results_same"] = results_same(build_dir)
            (tree / m["file"]).write_text(originals[m["file"]])  # put the file back
            record["seconds"] = round(time.monotonic() - t0, 1)
            keep(record)
            print(f"[{i + 1}/{len(mutants)}] {m['file']}:{m['line']} {m['operator']}: {record['outcome']}"
                  f"{' by ' + record['killer'] if record.get('killer') else ''} ({record['seconds']} s)",
                  flush=True)
    finally:
        results_file.close()
        for f, text in originals.items():
            (tree / f).write_text(text)
        build(build_dir, work / "build.log")
    lines = write_report([r for k, r in done.items() if k in wanted], report_path, command)
    print("\n".join(lines[:4 + len({module_of(f) for f in files}) + 1]))
    print(f"report: {report_path}")
    return 0


def tree_digest(tree, files):
    """Identifies the tests and sources the baseline was measured on."""
    h = hashlib.sha1()
    for sub in ("tests", "src", "include", "apps"):
        for f in sorted((tree / sub).rglob("*")):
            if f.is_file():
                h.update(str(f.relative_to(tree)).encode())
                h.update(f.read_bytes())
    return h.hexdigest()


if __name__ == "__main__":
    sys.exit(main())
