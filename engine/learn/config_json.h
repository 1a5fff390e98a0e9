#pragma once

// The learner's settings as JSON text, for checkpoints (and anything else that wants to show or
// store them). Parsing throws UserError naming the field that is missing or has the wrong type.

#include <string>

#include "engine/core/dataset.h"
#include "engine/learn/learner.h"

namespace recon::learn {

std::string ToJson(const NetworkConfig& network);
std::string ToJson(const TrainConfig& train);
std::string ToJson(const DataSpec& spec);

NetworkConfig NetworkConfigFromJson(const std::string& text);
TrainConfig TrainConfigFromJson(const std::string& text);
DataSpec DataSpecFromJson(const std::string& text);

}  // namespace recon::learn
