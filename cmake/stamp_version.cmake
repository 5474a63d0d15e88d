# Writes the project's version (pyproject.toml's, passed as VERSION) into the add-on copied to
# ADDON_DIR: blender_manifest.toml's version = "X.Y.Z" and bl_info's "version": (X, Y, Z).
# cmake -DADDON_DIR=... -DVERSION=X.Y.Z -P stamp_version.cmake
if(NOT VERSION MATCHES "^([0-9]+)\\.([0-9]+)\\.([0-9]+)")
  message(FATAL_ERROR "VERSION must start with X.Y.Z, not '${VERSION}'")
endif()
set(_tuple "(${CMAKE_MATCH_1}, ${CMAKE_MATCH_2}, ${CMAKE_MATCH_3})")

function(_stamp file regex replacement)
  file(READ "${file}" _text)
  string(REGEX MATCH "${regex}" _found "${_text}")
  if(NOT _found)
    message(FATAL_ERROR "${file}: no version line to stamp (${regex})")
  endif()
  string(REGEX REPLACE "${regex}" "${replacement}" _text "${_text}")
  file(WRITE "${file}" "${_text}")
endfunction()

_stamp("${ADDON_DIR}/blender_manifest.toml" "\nversion = \"[^\"]*\"" "\nversion = \"${VERSION}\"")
_stamp("${ADDON_DIR}/__init__.py" "\"version\": \\([0-9, ]*\\)" "\"version\": ${_tuple}")
