// libparallax.so: the module archives are linked in whole (cmake/Install.cmake); this file gives
// the library one symbol of its own, its version, so a consumer can check what it loaded.
namespace parallax {
extern "C" const char* parallax_library_version() { return PARALLAX_VERSION; }
}  // namespace parallax
