#include "engine/learn/config_json.h"

#include <nlohmann/json.hpp>

#include "engine/core/error.h"

namespace recon::learn {

using nlohmann::json;

namespace {

json Parse(const std::string& text, const char* what) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw UserError(std::string(what) + ": not valid JSON (" + e.what() + ")");
  }
}

template <typename T>
void Read(const json& j, const char* key, T& value, const char* what) {
  try {
    j.at(key).get_to(value);
  } catch (const json::exception& e) {
    throw UserError(std::string(what) + ": field '" + key + "' is missing or invalid (" + e.what() +
                    ")");
  }
}

}  // namespace

std::string ToJson(const NetworkConfig& n) {
  json j;
  j["feature_dim"] = n.feature_dim;
  j["conv_channels"] = n.conv_channels;
  j["conv_kernel"] = n.conv_kernel;
  j["cnn_hidden"] = n.cnn_hidden;
  j["image_scale"] = n.image_scale;
  j["spatial_softmax"] = n.spatial_softmax;
  j["action_chunk"] = n.action_chunk;
  j["ensembled_actions"] = n.ensembled_actions;
  j["feature_gate_hidden"] = n.feature_gate_hidden;
  j["feature_mlp_hidden"] = n.feature_mlp_hidden;
  j["policy_hidden"] = n.policy_hidden;
  j["beacon_hidden"] = n.beacon_hidden;
  return j.dump();
}

std::string ToJson(const TrainConfig& t) {
  json j;
  j["method"] = ToString(t.method);
  j["loss"] = ToString(t.loss);
  j["learning_rate"] = t.learning_rate;
  j["batch_size"] = t.batch_size;
  j["steps"] = t.steps;
  j["action_weight"] = t.action_weight;
  j["beacon_weight"] = t.beacon_weight;
  j["play_weight"] = t.play_weight;
  j["restart_rule"] = t.restart_rule;
  j["standardize_targets"] = t.standardize_targets;
  j["random_shift_px"] = t.random_shift_px;
  j["random_erase_px"] = t.random_erase_px;
  j["feature_noise"] = t.feature_noise;
  j["beacon_filter_samples"] = t.beacon_filter_samples;
  j["play_consistency"] = t.play_consistency;
  j["nll_min_std"] = t.nll_min_std;
  j["action_min_std"] = t.action_min_std;
  j["weight_decay"] = t.weight_decay;
  j["gate_margin"] = t.gate_margin;
  j["gate_target"] = ToString(t.gate_target);
  j["lr_schedule"] = ToString(t.lr_schedule);
  j["standardize_inputs"] = t.standardize_inputs;
  j["max_attempts"] = t.max_attempts;
  j["restart_action_threshold"] = t.restart_action_threshold;
  j["restart_beacon_threshold"] = t.restart_beacon_threshold;
  j["seed"] = t.seed;
  j["backend"] = ToString(t.backend);
  return j.dump();
}

std::string ToJson(const DataSpec& s) {
  json j;
  j["x_dim"] = s.x_dim;
  j["y_shape"] = s.y_shape;
  j["b_dim"] = s.b_dim;
  j["u_dim"] = s.u_dim;
  return j.dump();
}

NetworkConfig NetworkConfigFromJson(const std::string& text) {
  const char* what = "network config";
  const json j = Parse(text, what);
  NetworkConfig n;
  Read(j, "feature_dim", n.feature_dim, what);
  Read(j, "conv_channels", n.conv_channels, what);
  Read(j, "conv_kernel", n.conv_kernel, what);
  Read(j, "cnn_hidden", n.cnn_hidden, what);
  Read(j, "image_scale", n.image_scale, what);
  // Configs from before the layer existed have no such field: their networks had no layer.
  if (j.contains("spatial_softmax")) Read(j, "spatial_softmax", n.spatial_softmax, what);
  // Configurations from before chunking predict one action.
  if (j.contains("action_chunk")) Read(j, "action_chunk", n.action_chunk, what);
  // ... and, before the choice existed, acted on the ensemble of every action.
  if (j.contains("ensembled_actions")) Read(j, "ensembled_actions", n.ensembled_actions, what);
  // ... and had no gate.
  if (j.contains("feature_gate_hidden")) {
    Read(j, "feature_gate_hidden", n.feature_gate_hidden, what);
  }
  Read(j, "feature_mlp_hidden", n.feature_mlp_hidden, what);
  Read(j, "policy_hidden", n.policy_hidden, what);
  Read(j, "beacon_hidden", n.beacon_hidden, what);
  return n;
}

TrainConfig TrainConfigFromJson(const std::string& text) {
  const char* what = "train config";
  const json j = Parse(text, what);
  TrainConfig t;
  std::string method, loss;
  Read(j, "method", method, what);
  Read(j, "loss", loss, what);
  t.method = ParseMethod(method);
  t.loss = ParseLossKind(loss);
  Read(j, "learning_rate", t.learning_rate, what);
  Read(j, "batch_size", t.batch_size, what);
  Read(j, "steps", t.steps, what);
  Read(j, "action_weight", t.action_weight, what);
  Read(j, "beacon_weight", t.beacon_weight, what);
  Read(j, "play_weight", t.play_weight, what);
  Read(j, "restart_rule", t.restart_rule, what);
  Read(j, "standardize_targets", t.standardize_targets, what);
  Read(j, "max_attempts", t.max_attempts, what);
  Read(j, "restart_action_threshold", t.restart_action_threshold, what);
  Read(j, "restart_beacon_threshold", t.restart_beacon_threshold, what);
  Read(j, "seed", t.seed, what);
  // Checkpoints from before augmentation existed trained without it.
  if (j.contains("random_shift_px")) Read(j, "random_shift_px", t.random_shift_px, what);
  if (j.contains("random_erase_px")) Read(j, "random_erase_px", t.random_erase_px, what);
  if (j.contains("feature_noise")) Read(j, "feature_noise", t.feature_noise, what);
  // ... and on raw beacon readings, without play consistency.
  if (j.contains("beacon_filter_samples")) {
    Read(j, "beacon_filter_samples", t.beacon_filter_samples, what);
  }
  if (j.contains("play_consistency")) Read(j, "play_consistency", t.play_consistency, what);
  if (j.contains("nll_min_std")) Read(j, "nll_min_std", t.nll_min_std, what);
  if (j.contains("action_min_std")) Read(j, "action_min_std", t.action_min_std, what);
  // ... and without weight decay.
  if (j.contains("weight_decay")) Read(j, "weight_decay", t.weight_decay, what);
  if (j.contains("gate_margin")) Read(j, "gate_margin", t.gate_margin, what);
  // ... and, before the choice existed, gated by the loss.
  if (j.contains("gate_target")) {
    std::string gate_target;
    Read(j, "gate_target", gate_target, what);
    t.gate_target = ParseGateTarget(gate_target);
  }
  // ... and with a constant learning rate.
  if (j.contains("lr_schedule")) {
    std::string schedule;
    Read(j, "lr_schedule", schedule, what);
    t.lr_schedule = ParseLrSchedule(schedule);
  }
  if (j.contains("standardize_inputs")) {
    Read(j, "standardize_inputs", t.standardize_inputs, what);
  }
  // Checkpoints from before the Torch backend have no such field: they trained on our kernels.
  if (j.contains("backend")) {
    std::string backend;
    Read(j, "backend", backend, what);
    t.backend = ParseBackend(backend);
  }
  return t;
}

DataSpec DataSpecFromJson(const std::string& text) {
  const char* what = "data spec";
  const json j = Parse(text, what);
  DataSpec s;
  Read(j, "x_dim", s.x_dim, what);
  Read(j, "y_shape", s.y_shape, what);
  Read(j, "b_dim", s.b_dim, what);
  Read(j, "u_dim", s.u_dim, what);
  return s;
}

}  // namespace recon::learn
