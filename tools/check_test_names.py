#!/usr/bin/env python3
"""Every Catch2 test case must reach CTest whole.

catch_discover_tests registers each case under its name, and CMake cuts a name at `;`
(a list separator): such a case is registered under a fragment that matches no case, and
CTest reports it passed without running it. Lists every TEST_CASE whose name holds a `;`
and exits with 1 if there is any.
Usage: tools/check_test_names.py [ROOT]
"""

import pathlib
import re
import sys

TEST_CASE = re.compile(r'TEST_CASE\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)')
PIECE = re.compile(r'"((?:[^"\\]|\\.)*)"')


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    bad = 0
    for path in sorted((root / "tests").rglob("*.cpp")):
        text = path.read_text(encoding="utf-8")
        for match in TEST_CASE.finditer(text):
            name = "".join(PIECE.findall(match.group(1)))
            if ";" in name:
                line = text.count("\n", 0, match.start()) + 1
                print(f"{path.relative_to(root)}:{line}: test name holds ';', which CTest cuts: {name}")
                bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
