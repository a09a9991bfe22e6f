#!/usr/bin/env python3
"""Runs the workspace's test binaries two at a time, longest first: what `./run-tests` does after
`cargo test --no-run` has built them (cargo's JSON messages on stdin name them).

Why: `cargo test` runs one binary after another, and many of caustic's spend minutes in one or two
tests (a lavapipe compile, a long render), leaving the other core idle; on the 2-core CI machine the
binaries summed to 22 of `.ci/run`'s 26.5 minutes at 1.55 cores busy. Each binary runs as cargo runs
it (its package's directory as the working directory, its tests on their own threads), its output
printed whole when it ends, so that two never interleave. The last run's times
(`$CAUSTIC_CACHE/test-seconds.json`) order the next; a binary without one goes first.

Exit status: 0 when every binary passed; otherwise 1, after every binary has run and the failed
ones are named last. `CAUSTIC_TEST_JOBS` sets how many run at once (default 2).
"""
import json
import os
import subprocess
import sys
import threading
import time


def binaries(messages):
    """(label, executable, package directory) of every test binary in cargo's JSON messages."""
    found = []
    for line in messages:
        line = line.strip()
        if not line.startswith("{"):
            continue
        m = json.loads(line)
        if m.get("reason") != "compiler-artifact" or not m.get("executable"):
            continue
        if not m.get("profile", {}).get("test"):
            continue
        target = m["target"]
        package = os.path.dirname(m["manifest_path"])
        kind = "unit tests" if "lib" in target["kind"] or "bin" in target["kind"] else "tests"
        label = f"{os.path.basename(package)}: {target['name']} ({kind}, {target['kind'][0]})"
        found.append((label, m["executable"], package))
    return found


def main():
    cache = os.environ.get("CAUSTIC_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "caustic")
    times_file = os.path.join(cache, "test-seconds.json")
    try:
        with open(times_file) as f:
            last = json.load(f)
    except (OSError, ValueError):
        last = {}
    queue = binaries(sys.stdin)
    if not queue:
        print("error: no test binaries in cargo's messages", file=sys.stderr)
        return 1
    queue.sort(key=lambda b: -last.get(b[0], float("inf")))
    jobs = max(1, int(os.environ.get("CAUSTIC_TEST_JOBS", "2")))
    lock = threading.Lock()
    failed, seconds = [], {}
    start = time.monotonic()

    def worker():
        while True:
            with lock:
                if not queue:
                    return
                label, exe, cwd = queue.pop(0)
            clock = time.monotonic()
            run = subprocess.run([exe], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
            took = time.monotonic() - clock
            with lock:
                seconds[label] = round(took, 1)
                status = "ok" if run.returncode == 0 else f"FAILED (exit {run.returncode})"
                print(f"\n== {label}: {status} in {took:.1f} s", flush=True)
                sys.stdout.write(run.stdout.decode(errors="replace"))
                sys.stdout.flush()
                if run.returncode != 0:
                    failed.append(label)

    threads = [threading.Thread(target=worker) for _ in range(jobs)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    print(f"\n== {len(seconds)} test binaries in {time.monotonic() - start:.0f} s, {jobs} at a time")
    # Only a complete run's times order the next (a filtered run would record short ones).
    if not failed:
        try:
            os.makedirs(cache, exist_ok=True)
            with open(times_file + ".tmp", "w") as f:
                json.dump(seconds, f, indent=1, sort_keys=True)
            os.replace(times_file + ".tmp", times_file)
        except OSError as e:
            print(f"note: cannot record the tests' times in {times_file}: {e}", file=sys.stderr)
        return 0
    print("failed: " + ", ".join(failed), file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
