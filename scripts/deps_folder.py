"""Print the folder of cmake/deps' build for one target: one per machine, in the user's cache.

    python3 scripts/deps_folder.py KIND ZIG [FLAGS]

KIND names the target (``manylinux_2_28``, ``windows``); ZIG is the zig binary that compiles
it with the compiler flags FLAGS (those of the builder's wrappers that are not paths). The
folder's name carries a hash of cmake/deps/CMakeLists.txt (the sources' URLs and checksums,
the options), KIND, FLAGS and zig's version, so a change of any of them builds anew in
another folder, and every clone of the repository on this machine shares one build (the
builders write ``complete`` into the folder when it has built, and build under a lock on
the folder's name with ``.lock`` appended). The cache is ``$XDG_CACHE_HOME/geofair``
(default ``~/.cache/geofair``).
"""

import hashlib
import os
import pathlib
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent


def deps_folder(kind, zig, flags=""):
    """The folder (pathlib.Path) for target ``kind`` compiled by the zig binary ``zig`` with ``flags``."""
    version = subprocess.run([str(zig), "version"], capture_output=True, text=True, check=True).stdout.strip()
    digest = hashlib.sha256()
    digest.update((REPO / "cmake" / "deps" / "CMakeLists.txt").read_bytes())
    digest.update(f"\n{kind}\n{flags}\nzig {version}\n".encode())
    cache = pathlib.Path(os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache")
    return cache / "geofair" / f"deps-{kind}-{digest.hexdigest()[:12]}"


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    print(deps_folder(*sys.argv[1:]))
