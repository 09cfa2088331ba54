// The shared C library (librepose_c) is the static library linked whole (src/CMakeLists.txt), with only the
// repose_* functions exported (capi/exports.map). A shared library needs one source of its own: this one.
