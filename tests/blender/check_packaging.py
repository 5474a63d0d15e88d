"""Check that the add-on folder installs as a legacy add-on and, in Blender 4.2+, as an extension.

Zips ``<folder>/geometric_fairing`` the way the build does (``geometric_fairing/...``
inside the zip), then:

- legacy: Preferences › Add-ons › Install (``preferences.addon_install``) and
  enable ``geometric_fairing`` (``bl_info``; Blender 3.4 to 4.1, still accepted later);
- extension (4.2+): validate ``blender_manifest.toml`` with Blender's own
  ``blender_ext.py validate``, install from disk into the "User Default"
  repository and enable ``bl_ext.user_default.geometric_fairing``: relative
  imports only, the compiled module found inside the package, preferences
  under the package's name.

Each time the operator and fair_object must fair Suzanne's brow; the first one installed
must load the compiled module from its own folder (the second reuses it: pybind11
modules load once per process). The user folders are redirected to a temporary folder by the caller
(environment BLENDER_USER_RESOURCES, BLENDER_USER_SCRIPTS, BLENDER_USER_CONFIG)
so nothing is installed for the real user; the script refuses to run otherwise.
"""

import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import zipfile

import bpy

# isort: split
import addon_utils
import numpy as np

from geofair_dev.blender import add_subdivided_suzanne, parse_args, positions, select_faces

BROW = np.array([0.4, -0.7, 0.72])


def make_zip(folder, path):
    """Zip ``folder/geometric_fairing`` like the build: files under ``geometric_fairing/``."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for file in sorted((folder / "geometric_fairing").iterdir()):
            if file.is_file():
                archive.write(file, f"geometric_fairing/{file.name}")
    return path


def check_installed(module_name, user_folder, first=True):
    """The enabled add-on ``module_name`` runs from ``user_folder`` with its compiled module and preferences.

    ``first``: no other copy of the compiled module was loaded in this process before, so this
    package's own must be in use (a second copy cannot load: pybind11 types are per process,
    and the add-on then uses the copy already loaded).
    """
    module = sys.modules[module_name]
    package_dir = pathlib.Path(module.__file__).parent
    assert user_folder in package_dir.parents, f"{module_name} imported from {package_dir}, not the installed copy"
    assert module.native.geofair is not None, module.native.IMPORT_ERROR
    native_dir = pathlib.Path(module.native.geofair.__file__).parent
    assert (native_dir == package_dir) == first, f"compiled module from {native_dir}"
    preferences = bpy.context.preferences.addons[module_name].preferences
    assert type(preferences).bl_idname == module_name and preferences.tolerance > 0

    for obj in list(bpy.data.objects):  # (reading factory settings would disable the add-on)
        bpy.data.objects.remove(obj)
    obj = add_subdivided_suzanne()
    bpy.ops.object.mode_set(mode="EDIT")
    select_faces(obj, lambda c: np.linalg.norm(c - BROW) < 0.25)
    before = positions(obj)
    assert bpy.ops.mesh.geometric_fairing("EXEC_DEFAULT", inner_fairness="conformal") == {"FINISHED"}
    assert np.any(positions(obj) != before)
    bpy.ops.object.mode_set(mode="OBJECT")
    report = module.fair_object(obj, inner_fairness="conformal")  # the selection is still the brow
    assert report.converged, report
    print(f"ok: {module_name} from {package_dir}: operator and fair_object work ({report.summary()})")


def check_legacy(archive, user_folder, first):
    assert bpy.ops.preferences.addon_install(filepath=str(archive), overwrite=True) == {"FINISHED"}
    assert addon_utils.enable("geometric_fairing", default_set=True, handle_error=_raise) is not None
    check_installed("geometric_fairing", user_folder, first)
    addon_utils.disable("geometric_fairing", default_set=True, handle_error=_raise)
    installed = pathlib.Path(sys.modules["geometric_fairing"].__file__).parent
    shutil.rmtree(installed)  # (preferences.addon_remove needs a Preferences area)
    print("ok: installed, enabled and disabled as a legacy add-on")


def check_extension(archive, user_folder):
    validator = pathlib.Path(bpy.utils.system_resource("SCRIPTS")) / "addons_core" / "bl_pkg" / "cli" / "blender_ext.py"
    completed = subprocess.run(
        [sys.executable, str(validator), "validate", str(archive)], capture_output=True, text=True
    )
    assert completed.returncode == 0, completed.stdout + completed.stderr
    print(f"ok: blender_ext.py validate: {completed.stdout.strip()}")

    result = bpy.ops.extensions.package_install_files(
        filepath=str(archive), repo="user_default", enable_on_install=True
    )
    assert result == {"FINISHED"}, result
    name = "bl_ext.user_default.geometric_fairing"
    assert bpy.context.preferences.addons.get(name) is not None, [a.module for a in bpy.context.preferences.addons]
    check_installed(name, user_folder)
    addon_utils.disable(name, default_set=True, handle_error=_raise)
    result = bpy.ops.extensions.package_uninstall(repo_index=_repo_index("user_default"), pkg_id="geometric_fairing")
    assert result == {"FINISHED"}, result
    print("ok: installed, enabled, disabled and uninstalled as an extension")


def _repo_index(module):
    return next(i for i, repo in enumerate(bpy.context.preferences.extensions.repos) if repo.module == module)


def _raise(error):
    raise error


def main():
    folder, _ = parse_args()
    print(f"Blender {bpy.app.version_string}, Python {sys.version.split()[0]}, add-on from {folder}")
    user_folder = pathlib.Path(os.environ.get("BLENDER_USER_RESOURCES") or os.environ.get("BLENDER_USER_SCRIPTS", ""))
    user_scripts = pathlib.Path(bpy.utils.user_resource("SCRIPTS"))
    assert str(user_folder) not in ("", ".") and user_folder in (user_scripts, *user_scripts.parents), (
        f"redirect the user folders first (user scripts: {user_scripts})"
    )
    with tempfile.TemporaryDirectory() as temporary:
        archive = make_zip(folder, pathlib.Path(temporary) / "geometric_fairing.zip")
        extensions = bpy.app.version >= (4, 2, 0)
        if extensions:
            check_extension(archive, user_folder)
        check_legacy(archive, user_folder, first=not extensions)
    print("check_packaging: all checks passed")


main()
