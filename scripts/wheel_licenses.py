"""Add the copyright and licence texts of the libraries in a repaired wheel.

    python3 scripts/wheel_licenses.py dist/geofair-X.whl [NAME=LICENSE_FILE ...]

auditwheel's SBOM (``*.dist-info/sboms/auditwheel.cdx.json``) names the Debian package of
each library it copied into ``geofair.libs/``; that package's ``/usr/share/doc/<package>/copyright``
(the full copyright and licence texts) goes to ``*.dist-info/licenses/debian/<package>.copyright``,
and the wheel is packed again (``wheel pack`` writes its RECORD). Each NAME=LICENSE_FILE
(a library compiled into the module, e.g. OpenMesh and LLVM's libc++ in the manylinux_2_28
wheel) goes to ``*.dist-info/licenses/NAME.LICENSE``. docs/THIRD_PARTY_LICENSES.md sums them up.
"""

import json
import pathlib
import shutil
import subprocess
import sys
import tempfile


def debian_packages(unpacked):
    """Names of the Debian packages in auditwheel's SBOM of the unpacked wheel, sorted."""
    sboms = list(unpacked.glob("*.dist-info/sboms/auditwheel.cdx.json"))
    if not sboms:  # auditwheel bundled nothing
        return []
    components = json.loads(sboms[0].read_text()).get("components", [])
    return sorted({c["name"] for c in components if c.get("purl", "").startswith("pkg:deb/")})


def main():
    wheel = pathlib.Path(sys.argv[1])
    compiled_in = dict(arg.split("=", 1) for arg in sys.argv[2:])
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([sys.executable, "-m", "wheel", "unpack", "-d", folder, str(wheel)], check=True)
        (unpacked,) = pathlib.Path(folder).iterdir()
        (licenses,) = unpacked.glob("*.dist-info/licenses")
        packages = debian_packages(unpacked)
        if packages:
            (licenses / "debian").mkdir()
        for package in packages:
            shutil.copy(f"/usr/share/doc/{package}/copyright", licenses / "debian" / f"{package}.copyright")
        for name, path in compiled_in.items():
            shutil.copy(path, licenses / f"{name}.LICENSE")
        wheel.unlink()
        subprocess.run([sys.executable, "-m", "wheel", "pack", "-d", str(wheel.parent), str(unpacked)], check=True)
    print(f"{wheel.name}: the licences of {', '.join(packages + list(compiled_in)) or 'nothing'} added")


if __name__ == "__main__":
    main()
