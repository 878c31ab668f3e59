#pragma once
// The station's live feed as Foxglove channels (app/foxglove/channels.hpp): the vehicle's pose,
// frame transform, position and navigation at the telemetry rate, the turn being flown with its
// predictions, the operating region, and events as logs. What is sent and when is decided here;
// the transport (server/foxglove_hub.hpp) only fans the messages out to its clients.

#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/foxglove/channels.hpp"
#include "app/foxglove/messages.hpp"
#include "app/foxglove_scene.hpp"
#include "app/live_feed.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::app::foxglove {

// Where the live messages go. Calls come from the vehicle loop's thread and must not block.
class FoxgloveSink {
 public:
  virtual ~FoxgloveSink() = default;
  virtual void advertise(const std::string& vehicle_id,
                         const std::vector<ChannelSpec>& channels) = 0;
  virtual void unadvertise(const std::string& vehicle_id) = 0;
  // Whether any client listens to the topic: a message nobody wants is not built.
  virtual bool wanted(const std::string& topic) const = 0;
  virtual void publish(const std::string& topic, std::uint64_t t_ns, std::string payload) = 0;
  // The protocol's status message, for what an operator reads in Foxglove's problem list.
  virtual void status(LogLevel level, const std::string& message) = 0;
  // The station clock, which runs faster than real time on a simulator.
  virtual void time(std::uint64_t t_ns) = 0;
};

// The predictions a turn's scene shows; Station passes app::foxglove::scene_predictions.
using TurnPredictor =
    std::function<ScenePredictions(const std::string& vehicle_id, double speed_mps,
                                   double dheading_deg, const kinematics::Pose& start)>;

class FoxgloveLive final : public LiveFeed {
 public:
  // datum: where the grid lies on the earth, for a vehicle whose navigation carries no latitude
  // and longitude of its own (the simulator); none: positions only as the vehicle reports them.
  FoxgloveLive(FoxgloveSink& sink, TurnPredictor predictor,
               std::optional<vehicle::LatLon> datum = std::nullopt);
  ~FoxgloveLive() override;

  void telemetry(const VehicleSnapshot& s) override;
  void station_event(double t_s, mission::EventKind kind, const std::string& message) override;
  std::unique_ptr<mission::MissionObserver> follow(std::int64_t mission_id,
                                                   const mission::MissionRunner& runner) override;

  // Every vehicle's channels go away (the station is stopping). Waits for a turn's predictions
  // still being computed: call it before what the predictor uses (the Context) goes.
  void withdraw();

  // How often the scene of a running turn is redrawn with its measured track, station clock.
  double turn_redraw_interval_s = 1.0;

 private:
  class MissionChannels;
  friend class MissionChannels;

  void turn_started(const mission::RunningTurn& turn);
  void turn_ended(const mission::TurnOutcome& t);
  void publish_turn_scene();
  void log(double t_s, mission::EventKind kind, const std::string& message);

  FoxgloveSink& sink_;
  TurnPredictor predictor_;
  // The predictions of the turn just started, computed beside the vehicle loop: a table that must
  // be rebuilt first must not hold up the helm at the very moment it commands a turn.
  std::future<void> predicting_;
  std::uint64_t turn_number_ = 0;  // which turn the scene shows
  std::optional<vehicle::LocalGrid> grid_;
  std::mutex mutex_;
  std::optional<std::string> advertised_;  // the vehicle whose channels are offered
  std::optional<vehicle::NavSample> last_nav_;
  std::optional<TurnScene> turn_;
  bool turn_running_ = false;
  double turn_drawn_t_s_ = 0.0;
};

}  // namespace avk::app::foxglove
