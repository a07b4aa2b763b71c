// mrqp drivers -- frame routing (setup).
#include "mrqp/drivers/bus_router.hpp"

namespace mrqp::drivers {

BusRouter::BusRouter(Bus& bus, std::size_t max_handlers, std::size_t max_frames_per_poll)
    : bus_(&bus),
      handlers_(max_handlers > 0 ? max_handlers : 1, nullptr),
      max_frames_per_poll_(max_frames_per_poll > 0 ? max_frames_per_poll : 1) {}

}  // namespace mrqp::drivers
