#!/usr/bin/env python3
"""ctest, quietly: what `make test` shows of a ctest run.

    scripts/ctest_quiet.py [--verbose] -- <ctest arguments>

Runs ctest with --output-on-failure and prints what needs reading: every
failed test's output in full, one line per skipped test with its reason (the
line the test printed, `skipped: ...`), any memcheck defects, and ctest's
summary. A passed test is not listed. ctest's whole output goes to
<test dir>/Testing/Temporary/ctest-quiet.log as well; --verbose (make V=1)
prints all of it. The exit status is ctest's.
"""

import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

# ctest's per-test status lines, which say nothing once the summary is read:
#   "      Start  12: test_transform"
#   " 12/212 Test  #12: test_transform ...........   Passed    0.02 sec"
START = re.compile(r"^\s*Start\s+\d+: ")
PASSED = re.compile(r"^\s*\d+/\d+ (Test|MemCheck)\s+#\d+: .* Passed\s+[0-9.]+ sec$")
SKIPPED = re.compile(r"^\s*\d+/\d+ (?:Test|MemCheck)\s+#\d+: (\S+) .*Skipped\s+[0-9.]+ sec$")
# What `ctest -T memcheck` says of the dashboard it would submit to (there is
# none): no test's business.
DASHBOARD = re.compile(r"^(Cannot find file: .*DartConfiguration\.tcl|\s+Site: |\s+Build name: |"
                       r"Create new tag: |Memory check project )")


def test_dir(args):
    if "--test-dir" in args:
        return pathlib.Path(args[args.index("--test-dir") + 1])
    return pathlib.Path.cwd()


def skip_reasons(skipped_names, junit):
    """{test name: reason} for the tests ctest reported skipped (not those it
    could not run, which are failures), from its JUnit file: the test's own
    line 'skipped: ...' when it printed one, else ctest's message."""
    reasons = {name: "skipped: no reason given" for name in skipped_names}
    try:
        root = ET.parse(junit).getroot()
    except (OSError, ET.ParseError):
        return reasons
    for case in root.iter("testcase"):
        if case.get("name") not in reasons:
            continue
        skipped = case.find("skipped")
        output = case.findtext("system-out") or ""
        said = [line.strip() for line in output.splitlines() if line.strip().startswith("skipped:")]
        if said:
            reasons[case.get("name")] = said[-1]
        else:
            message = skipped.get("message") if skipped is not None else None
            reasons[case.get("name")] = "skipped: " + (message or "no reason given")
    return reasons


def quiet(lines, reasons):
    """ctest's output without the lines of passed tests, its header, its
    per-label times and its list of tests that did not run (the skipped are
    listed with their reasons instead)."""
    out = []
    dropping = False  # inside a block dropped up to its blank line
    for line in lines:
        if dropping:
            dropping = line.strip() != ""
            continue
        if line.startswith("Label Time Summary:") or line.startswith("The following tests did not run:"):
            dropping = True
            continue
        if line.startswith(("Test project ", "Internal ctest changing into directory")):
            continue
        if DASHBOARD.match(line):
            continue
        if START.match(line) or PASSED.match(line) or SKIPPED.match(line):
            continue
        out.append(line)
    # Collapse the runs of blank lines the dropped lines leave.
    text = re.sub(r"\n{3,}", "\n\n", "\n".join(out)).strip("\n")
    skipped = [f"{name}: {reason}" for name, reason in sorted(reasons.items())]
    return "\n".join(skipped + ([text] if text else []))


def main(argv):
    verbose = False
    if argv and argv[0] == "--verbose":
        verbose, argv = True, argv[1:]
    if argv and argv[0] == "--":
        argv = argv[1:]
    logdir = test_dir(argv) / "Testing" / "Temporary"
    logdir.mkdir(parents=True, exist_ok=True)
    log, junit = logdir / "ctest-quiet.log", logdir / "ctest-quiet.junit.xml"
    junit.unlink(missing_ok=True)
    cmd = ["ctest", "--output-on-failure", "--output-junit", str(junit.resolve())] + argv
    result = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            errors="replace")
    log.write_text(result.stdout)
    if verbose:
        sys.stdout.write(result.stdout)
    else:
        lines = result.stdout.splitlines()
        skipped = [m.group(1) for m in map(SKIPPED.match, lines) if m]
        print(quiet(lines, skip_reasons(skipped, junit)))
        if result.returncode != 0:
            print(f"(ctest's whole output: {log})")
    return result.returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
