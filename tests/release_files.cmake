# The release files agree with the one version, CMake's project(strictmin VERSION ...):
# CITATION.cff's `version:` and a `## [VERSION]` section in CHANGELOG.md (cmake -P; inputs
# SOURCE_DIR VERSION).
file(STRINGS ${SOURCE_DIR}/CITATION.cff cff_version REGEX "^version:")
if(NOT cff_version MATCHES "^version: \"?${VERSION}\"?$")
  message(FATAL_ERROR "CITATION.cff says '${cff_version}', CMake's version is ${VERSION}")
endif()
file(STRINGS ${SOURCE_DIR}/CHANGELOG.md releases REGEX "^## \\[[0-9]")
list(GET releases 0 newest)
if(NOT newest MATCHES "^## \\[${VERSION}\\] - [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]$")
  message(FATAL_ERROR "CHANGELOG.md's newest release is '${newest}', CMake's version is ${VERSION}")
endif()
foreach(f LICENSE CITATION.cff CHANGELOG.md)
  if(NOT EXISTS ${SOURCE_DIR}/${f})
    message(FATAL_ERROR "${f} is missing")
  endif()
endforeach()
