#!/usr/bin/env python3
"""Kills, full disks and concurrent runs against `garment-retarget retarget`'s result folder.

Each case runs the bundled scene under strace, which kills the program (SIGKILL) at the
Nth call of one system call that writes a file or changes a folder, or fails the Nth write
with ENOSPC, for every N the run makes (writes with --stride, every other call always). After each case the folder must hold one run's
complete result, the earlier one, or nothing: a certificate always describes the garment
beside it (its SHA-256), a garment never stands without its certificate, and no staging
folder survives the next run.

usage: test_interrupted_runs.py PROGRAM SCENE_DIR WORK_DIR [--stride K]
"""

from __future__ import annotations

import argparse
import collections
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

# The calls that write files (libstdc++ streams write large buffers with writev, and
# std::filesystem copies with sendfile or copy_file_range) and those that change folders.
WRITE_CALLS = ["write", "writev", "pwrite64", "sendfile", "copy_file_range"]
FOLDER_CALLS = ["rename", "renameat", "renameat2", "mkdir", "unlink", "unlinkat", "rmdir"]
KILLED = -9


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


class Scene:
    def __init__(self, program: str, scene: Path):
        self.program = program
        self.scene = scene

    def arguments(self, out: Path, quality: str = "fast") -> list[str]:
        s = self.scene
        return [self.program, "retarget", "--garment", str(s / "garment.obj"), "--avatar",
                str(s / "avatar.obj"), "--no-fit", str(s / "no-fit.txt"), "--out", str(out),
                "--quality", quality, "--threads", "1", "--quiet"]


def run(arguments: list[str], inject: str | None = None) -> int:
    command = arguments
    if inject:
        command = ["strace", "-f", "-qq", "-o", "/dev/null", "-e", f"inject={inject}"] + arguments
    return subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode


def call_counts(arguments: list[str], trace: Path) -> collections.Counter:
    """How often each traced call happens in one run (all threads)."""
    calls = ",".join(WRITE_CALLS + FOLDER_CALLS)
    subprocess.run(["strace", "-f", "-qq", "-o", str(trace), "-e", f"trace={calls}"] + arguments,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    counts: collections.Counter = collections.Counter()
    for line in trace.read_text().splitlines():
        match = re.match(r"^\d+\s+(\w+)\(", line)
        if match:
            counts[match.group(1)] += 1
    return counts


def folder_problems(out: Path, allowed_digests: set[str], may_be_missing: bool) -> list[str]:
    """What is wrong with `out` after an interrupted run; empty when it is whole."""
    if not out.exists():
        return [] if may_be_missing else ["the earlier result is gone"]
    problems = []
    garment, certificate, report = out / "garment.obj", out / "certificate.json", out / "report.json"
    if not report.is_file():
        problems.append("no report.json")
    if garment.exists() and not certificate.exists():
        problems.append("a garment without its certificate")
    if certificate.exists():
        try:
            recorded = json.loads(certificate.read_text())["extra"]["output"]["sha256"]
        except (ValueError, KeyError) as error:
            return problems + [f"certificate.json unreadable: {error}"]
        if not garment.is_file():
            problems.append("a certificate without its garment")
        elif sha256(garment) != recorded:
            problems.append("the certificate describes another garment")
        elif recorded not in allowed_digests:
            problems.append("a garment from neither run")
    if (out / "garment.mtl").exists() and (out / "garment.mtl").stat().st_size == 0:
        problems.append("an empty garment.mtl")
    return problems


def staging_left(out: Path) -> list[str]:
    return [p.name for p in out.parent.iterdir() if p.name.startswith(f".{out.name}.tmp-")]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program")
    parser.add_argument("scene", type=Path)
    parser.add_argument("work", type=Path)
    parser.add_argument("--stride", type=int, default=1, help="kill at every K-th write")
    options = parser.parse_args()
    scene = Scene(os.path.abspath(options.program), options.scene)
    work = options.work
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    # The two results a folder may hold: an earlier one (balanced) and the new one (fast).
    reference_new, reference_old = work / "reference_new", work / "reference_old"
    assert run(scene.arguments(reference_new)) == 0
    assert run(scene.arguments(reference_old, "balanced")) == 0
    new_digest = sha256(reference_new / "garment.obj")
    old_digest = sha256(reference_old / "garment.obj")
    assert new_digest != old_digest, "the two presets must write different garments"

    counts = call_counts(scene.arguments(work / "counted"), work / "trace.txt")
    print("calls in one run:", dict(counts))
    failures: list[str] = []
    cases = 0
    injected: collections.Counter = collections.Counter()  # runs the injection ended early

    def check(label: str, out: Path, exit_code: int, expected_codes: set[int], earlier: bool):
        nonlocal cases
        cases += 1
        allowed = {new_digest, old_digest} if earlier else {new_digest}
        problems = folder_problems(out, allowed, may_be_missing=not earlier)
        if exit_code not in expected_codes:
            problems.append(f"exit code {exit_code}")
        if problems:
            failures.append(f"{label}: {'; '.join(problems)}")

    for earlier in (False, True):
        for call, count in sorted(counts.items()):
            stride = options.stride if call in WRITE_CALLS else 1
            for when in range(1, count + 1, stride):
                for action, codes in (("signal=SIGKILL", {KILLED, 0}), ("error=ENOSPC", {0, 5})):
                    if action.startswith("error") and call not in WRITE_CALLS + ["mkdir"]:
                        continue
                    out = work / "out"
                    shutil.rmtree(out, ignore_errors=True)
                    if earlier:
                        shutil.copytree(reference_old, out)
                    code = run(scene.arguments(out), f"{call}:{action}:when={when}")
                    injected[call] += code != 0
                    label = f"{'earlier' if earlier else 'fresh'} {call} #{when} {action}"
                    check(label, out, code, codes, earlier)
                    # The next run cleans up after the interrupted one and ends whole.
                    if code != 0 and when % 7 == 1:
                        check(label + ", then a full run", out, run(scene.arguments(out)), {0},
                              earlier)
                        if staging_left(out):
                            failures.append(f"{label}: staging left after the next run")
            for leftover in work.glob(".out.tmp-*"):
                shutil.rmtree(leftover)

    # Two runs into one folder at once: one may be refused (exit 5), none may mix.
    for attempt in range(6):
        out = work / "concurrent"
        shutil.rmtree(out, ignore_errors=True)
        first = subprocess.Popen(scene.arguments(out), stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
        second = subprocess.Popen(scene.arguments(out, "balanced"), stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL)
        codes = (first.wait(), second.wait())
        cases += 1
        problems = folder_problems(out, {new_digest, old_digest}, may_be_missing=False)
        if not set(codes) <= {0, 5} or 0 not in codes:
            problems.append(f"exit codes {codes}")
        if codes == (0, 5) and out.exists() and sha256(out / "garment.obj") != new_digest:
            problems.append("the refused run's garment is in the folder")
        if codes == (5, 0) and out.exists() and sha256(out / "garment.obj") != old_digest:
            problems.append("the refused run's garment is in the folder")
        if problems:
            failures.append(f"concurrent #{attempt}: {'; '.join(problems)}")

    # Every traced call must have ended some run early, or the injection did nothing.
    for call in counts:
        if injected[call] == 0:
            failures.append(f"no injection at {call} ended a run: is strace's inject working?")
    print(f"{cases} cases, {len(failures)} failed; runs ended early per call: {dict(injected)}")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
