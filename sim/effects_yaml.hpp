// The `effects:` section of a scenario (scenarios/SCHEMA.md): a preset name
// (ideal, realistic, randomized), or a map of keys with an optional `preset` to start
// from. Per-chain keys take a scalar (all three chains) or a list of three.
#pragma once

#include <cstdint>
#include <string>

#include <yaml-cpp/yaml.h>

#include "models/data_sheet.hpp"
#include "sim/effects.hpp"

namespace gpm::sim {

// Parses node (at key path `effects` of file). Encoder phases are drawn from
// gpm::Rng seeded by derive_seed(seed, Stream::kEncoderErrors), one per encoder; the phases of the
// encoder harmonics from derive_seed(seed, Stream::kHarmonicPhases), one per slot and encoder. Throws
// InputError naming the file, line and key for a bad value or unknown key.
Effects parse_effects(const YAML::Node& node, const std::string& file, std::uint64_t seed,
                      const DataSheet& sheet = {});

}  // namespace gpm::sim
