// mrqp drivers -- in-process CAN bus: construction (allocates; not for the control cycle).
#include "mrqp/drivers/sim_bus.hpp"

namespace mrqp::drivers {

SimNode::SimNode(SimBus& bus, std::size_t index, const SimNodeConfig& config)
    : bus_(&bus),
      index_(index),
      config_(config),
      tx_(config.tx_queue > 0 ? config.tx_queue : 1),
      rx_(config.rx_queue > 0 ? config.rx_queue : 1) {}

SimNode::~SimNode() = default;

SimBus::SimBus(const SimBusConfig& config) : config_(config) {
  if (config_.nominal_bps == 0u) {
    config_.nominal_bps = 1000000u;
  }
  if (config_.max_nodes == 0u) {
    config_.max_nodes = 1u;
  }
  occurrence_ns_ = static_cast<TimeNs>((11000000000ull + config_.nominal_bps - 1u) / config_.nominal_bps);
  nodes_.reserve(config_.max_nodes);
  participants_.assign(config_.max_nodes, 0u);
}

SimBus::~SimBus() = default;

SimNode* SimBus::addNode(const SimNodeConfig& config) {
  if (nodes_.size() >= config_.max_nodes) {
    return nullptr;
  }
  nodes_.push_back(std::unique_ptr<SimNode>(new SimNode(*this, nodes_.size(), config)));
  return nodes_.back().get();
}

}  // namespace mrqp::drivers
