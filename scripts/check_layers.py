"""Check the include layers of native/: the library's internal headers sit below its API.

    python3 scripts/check_layers.py

The public headers in native/include/geofair/ are of two kinds. The bottom ones (BOTTOM
below: errors.h, the exceptions; tuning.h, the solver tuning; types.h, the types shared by
the algorithms and the API) include no other geofair/ header outside BOTTOM. The API headers
(fairing.h, building_blocks.h, hole_filling.h, live.h, ...) declare the library's functions
and include whatever they need. An internal header in native/src/ may include a bottom
header, never an API one: the algorithms do not depend on the face they are exported
through. (Sources in native/src/ may include the API header that they implement.)

Fails (exit 1) with one line per offending include, naming the file, the line and the
header; prints nothing and exits 0 when the layers are clean.
"""

import pathlib
import re
import sys

BOTTOM = {"errors.h", "tuning.h", "types.h"}
NATIVE = pathlib.Path(__file__).resolve().parent.parent / "native"
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]geofair/([^">]+)[">]')


def offending(header: pathlib.Path) -> list[str]:
    """The includes of a geofair/ header outside BOTTOM in `header`, as report lines."""
    found = []
    for number, line in enumerate(header.read_text(encoding="utf-8").splitlines(), 1):
        match = INCLUDE.match(line)
        if match and match.group(1) not in BOTTOM:
            where = header.relative_to(NATIVE.parent)
            found.append(f"{where}:{number}: includes geofair/{match.group(1)}")
    return found


def main() -> int:
    headers = sorted((NATIVE / "src").glob("*.h"))
    headers += [NATIVE / "include" / "geofair" / name for name in sorted(BOTTOM)]
    problems = [line for header in headers for line in offending(header)]
    for line in problems:
        print(f"{line}, a public header above the bottom ones ({', '.join(sorted(BOTTOM))})")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
