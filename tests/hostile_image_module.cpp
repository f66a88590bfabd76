// Broken image modules for the hostile suite: HEADLIGHT_IMAGE_MODULE names
// one of these, and render and diff must refuse it before calling into it.
// HOSTILE_TABLE 0: the entry returns NULL; 1: a table of another size.
#include <cstdint>

namespace {
struct WrongTable {
  std::uint32_t abi, tableSize;
  void* functions[2];
};
const WrongTable kWrongTable{2, sizeof(WrongTable), {nullptr, nullptr}};
}  // namespace

extern "C" __attribute__((visibility("default"))) const void* headlightImageModuleTable() {
#if HOSTILE_TABLE == 0
  return nullptr;
#else
  return &kWrongTable;
#endif
}
