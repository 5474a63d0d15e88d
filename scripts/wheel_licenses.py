"""Add the copyright and licence texts of the libraries auditwheel bundled to a repaired wheel.

    python3 scripts/wheel_licenses.py dist/geofair-*.whl

auditwheel's SBOM (``*.dist-info/sboms/auditwheel.cdx.json``) names the Debian package of
each library it copied into ``geofair.libs/``; that package's ``/usr/share/doc/<package>/copyright``
(the full copyright and licence texts) goes to ``*.dist-info/licenses/debian/<package>.copyright``,
and the wheel is packed again (``wheel pack`` writes its RECORD). docs/THIRD_PARTY_LICENSES.md
sums them up.
"""

import json
import pathlib
import shutil
import subprocess
import sys
import tempfile


def debian_packages(unpacked):
    """Names of the Debian packages in auditwheel's SBOM of the unpacked wheel, sorted."""
    (sbom,) = unpacked.glob("*.dist-info/sboms/auditwheel.cdx.json")
    components = json.loads(sbom.read_text())["components"]
    return sorted({c["name"] for c in components if c.get("purl", "").startswith("pkg:deb/")})


def main():
    (wheel,) = (pathlib.Path(arg) for arg in sys.argv[1:])
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([sys.executable, "-m", "wheel", "unpack", "-d", folder, str(wheel)], check=True)
        (unpacked,) = pathlib.Path(folder).iterdir()
        (licenses,) = unpacked.glob("*.dist-info/licenses")
        (licenses / "debian").mkdir()
        packages = debian_packages(unpacked)
        for package in packages:
            shutil.copy(f"/usr/share/doc/{package}/copyright", licenses / "debian" / f"{package}.copyright")
        wheel.unlink()
        subprocess.run([sys.executable, "-m", "wheel", "pack", "-d", str(wheel.parent), str(unpacked)], check=True)
    print(f"{wheel.name}: the licences of {', '.join(packages)} added")


if __name__ == "__main__":
    main()
