#include "uampc/dynamixel/control_table.hpp"

#include <cmath>

namespace uampc::dynamixel {
namespace {
constexpr double kTwoPi = 6.283185307179586;
}

std::string hardwareErrorText(std::uint8_t status) {
  static const char* const kBits[8] = {"input voltage error", nullptr,    "overheating", "motor encoder error",
                                       "electrical shock",    "overload", nullptr,       nullptr};
  std::string text;
  for (int bit = 0; bit < 8; ++bit) {
    if (!(status & (1u << bit))) continue;
    if (!text.empty()) text += ", ";
    text += kBits[bit] ? kBits[bit] : "bit " + std::to_string(bit);
  }
  return text;
}

// Model numbers, 0.229 rev/min per velocity unit and 4096 counts per turn, from the models' e-manual
// control tables.
const std::vector<Model>& knownModels() {
  static const std::vector<Model> kModels = {
      {"XL430-W250", 1060, 0.229, 4096}, {"XM430-W210", 1030, 0.229, 4096}, {"XM430-W350", 1020, 0.229, 4096},
      {"XM540-W150", 1130, 0.229, 4096}, {"XM540-W270", 1120, 0.229, 4096}, {"XH430-W210", 1000, 0.229, 4096},
      {"XH430-W350", 1010, 0.229, 4096},
  };
  return kModels;
}

const Model* modelByName(const std::string& name) {
  for (const auto& m : knownModels())
    if (m.name == name) return &m;
  return nullptr;
}

const Model* modelByNumber(std::uint16_t number) {
  for (const auto& m : knownModels())
    if (m.number == number) return &m;
  return nullptr;
}

std::string knownModelNames() {
  std::string names;
  for (const auto& m : knownModels()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

double radiansPerSecond(const Model& model, std::int32_t velocity_units) {
  return velocity_units * model.velocity_unit_rpm * kTwoPi / 60.0;
}

std::int32_t velocityUnits(const Model& model, double radians_per_second) {
  return static_cast<std::int32_t>(std::lround(radians_per_second * 60.0 / (kTwoPi * model.velocity_unit_rpm)));
}

double radians(const Model& model, std::int64_t counts) {
  return static_cast<double>(counts) * kTwoPi / model.counts_per_turn;
}

}  // namespace uampc::dynamixel
