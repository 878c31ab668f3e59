// A mission as an MCAP recording and back: a small simulated mission exported, read with the
// station's reader, imported into another database and compared field by field.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/context.hpp"
#include "app/current.hpp"
#include "app/foxglove/channels.hpp"
#include "app/mcap/reader.hpp"
#include "app/mcap/writer.hpp"
#include "app/mission_legs.hpp"
#include "app/mission_mcap.hpp"
#include "app/store_access.hpp"
#include "store/sqlite.hpp"
#include "support/mcap_bytes.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
using nlohmann::json;

constexpr const char* kVehicle = "usim-mcap";

// One recorded mission with a significant current stored (its turns in the water frame), shared
// by the tests: flying it is the expensive part.
class MissionMcapTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    source_ = new avk::testing::TempDb("avk_mcap_source");
    ctx_ = new app::Context(source_->path());
    store::Store& db = app::store_of(*ctx_);
    mission_ = avk::testing::run_recorded_mission(db, kVehicle);
    store::StoredCurrent c;
    c.mission_id = mission_;
    c.t_s = db.missions().clock_end_s(mission_).value_or(0.0);
    c.estimate.east_mps = 0.21;
    c.estimate.north_mps = -0.13;
    c.estimate.covariance = {1e-4, 2e-6, 1.5e-4};
    c.estimate.speed_scale = 0.987654321;
    c.estimate.residual_rms_mps = 0.0123;
    c.estimate.legs = 7;
    c.speed_reference = kinematics::SpeedReferenceEvidence{
        9, 0.0123456789, 0.2, 0.15, kinematics::SpeedReference::through_water};
    c.drift_scatter = kinematics::DriftScatter{0.0456, 0.0321, 8, 11.25};
    ASSERT_TRUE(app::current_is_significant(c.estimate));
    std::vector<std::pair<std::int64_t, kinematics::TurnSequence>> ok;
    app::for_each_mission_turn(
        db, mission_, kinematics::TurnStatus::ok,
        [&](const store::TurnRow& t) { ok.emplace_back(t.id, db.turns().get(t.id)->raw); });
    db.currents().save(c, app::water_frame_turns(ok, app::water_current(c.estimate)));
  }
  static void TearDownTestSuite() {
    delete ctx_;
    delete source_;
  }

  static app::McapExport exported(const app::McapExportOptions& o = {}) {
    auto r = app::export_mission_mcap(*ctx_, mission_, o);
    EXPECT_TRUE(r) << r.error().message;
    return std::move(r).value();
  }

  static avk::testing::TempDb* source_;
  static app::Context* ctx_;
  static std::int64_t mission_;
};

avk::testing::TempDb* MissionMcapTest::source_ = nullptr;
app::Context* MissionMcapTest::ctx_ = nullptr;
std::int64_t MissionMcapTest::mission_ = 0;

std::string topic(app::foxglove::ChannelKind k) {
  return app::foxglove::topic(kVehicle, k);
}

std::int64_t count_rows(const std::string& db_path, const std::string& table) {
  store::Connection c(db_path);
  auto s = c.prepare("SELECT count(*) FROM " + table);
  s.step();
  return s.column_int64(0);
}

std::map<std::string, std::int64_t> all_counts(const std::string& db_path) {
  std::map<std::string, std::int64_t> out;
  for (const char* t : {"vehicles", "missions", "nav_samples", "turns", "mission_events",
                        "condition_sets", "mission_currents"})
    out[t] = count_rows(db_path, t);
  return out;
}

std::vector<store::MissionEvent> events_of(store::Store& db, std::int64_t mission) {
  return db.missions().events(mission, 0, 100000);
}

std::vector<store::TurnRow> turns_of(store::Store& db, std::int64_t mission) {
  store::TurnFilter f;
  f.mission_id = mission;
  f.limit = 100000;
  return db.turns().list(f);
}

void expect_same_row(const store::TurnRow& a, const store::TurnRow& b) {
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.cell_speed_mps, b.cell_speed_mps);
  EXPECT_EQ(a.cell_dheading_deg, b.cell_dheading_deg);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.commanded_speed_mps, b.commanded_speed_mps);
  EXPECT_EQ(a.goal_dheading_deg, b.goal_dheading_deg);
  EXPECT_EQ(a.observed_dheading_deg, b.observed_dheading_deg);
  EXPECT_EQ(a.start_time_s, b.start_time_s);
  EXPECT_EQ(a.end_time_s, b.end_time_s);
  EXPECT_EQ(a.advance_m, b.advance_m);
  EXPECT_EQ(a.transfer_m, b.transfer_m);
  EXPECT_EQ(a.condition_set_time_s, b.condition_set_time_s);
  EXPECT_EQ(a.start_heading_error_deg, b.start_heading_error_deg);
  EXPECT_EQ(a.start_yaw_rate_dps, b.start_yaw_rate_dps);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.quality, b.quality);
  EXPECT_EQ(a.speed_after_mps, b.speed_after_mps);
}

// The file re-written with the station's writer after `edit` changed its contents: a file that
// is valid MCAP but whose content is wrong in one place.
std::string rewritten(const std::string& bytes,
                      const std::function<void(app::mcap::McapContents&)>& edit) {
  auto c = app::mcap::read_mcap(bytes);
  edit(c);
  // The reader lists them in file order (a channel is written where it is first used); the
  // writer numbers them in call order.
  std::ranges::sort(c.schemas, {}, &app::mcap::SchemaRecord::id);
  std::ranges::sort(c.channels, {}, &app::mcap::ChannelRecord::id);
  app::mcap::WriterOptions o;
  o.compression = app::mcap::Compression::none;
  app::mcap::Writer w(o);
  for (const auto& s : c.schemas)
    EXPECT_EQ(w.add_schema(s.name, s.encoding, s.data), s.id);
  for (const auto& ch : c.channels)
    EXPECT_EQ(w.add_channel(ch.schema_id, ch.topic, ch.message_encoding, ch.metadata), ch.id);
  for (const auto& m : c.messages)
    w.add_message(m.channel_id, m.log_time_ns, m.publish_time_ns, m.data);
  for (const auto& m : c.metadata)
    w.add_metadata(m.name, m.entries);
  return w.finish();
}

std::uint16_t channel_id(const app::mcap::McapContents& c, app::foxglove::ChannelKind k) {
  for (const auto& ch : c.channels)
    if (ch.topic == topic(k)) return ch.id;
  ADD_FAILURE() << "no channel " << topic(k);
  return 0;
}

TEST_F(MissionMcapTest, ExportThenImportGivesTheSameMissionFieldByField) {
  const app::McapExport e = exported();
  avk::testing::TempDb target("avk_mcap_target");
  app::Context to(target.path());
  const auto imported = app::import_mission_mcap(to, e.bytes);
  ASSERT_TRUE(imported) << imported.error().message;
  const std::int64_t id = imported->mission_id;
  EXPECT_EQ(imported->source_mission_id, mission_);

  store::Store& a = app::store_of(*ctx_);
  store::Store& b = app::store_of(to);
  const auto ma = *a.missions().get(mission_);
  const auto mb = *b.missions().get(id);
  EXPECT_EQ(mb.vehicle_id, ma.vehicle_id);
  EXPECT_EQ(mb.name, ma.name);
  EXPECT_EQ(mb.config_json, ma.config_json);
  EXPECT_EQ(mb.status, ma.status);
  EXPECT_EQ(mb.status_reason, ma.status_reason);
  EXPECT_EQ(mb.created_utc, ma.created_utc);
  EXPECT_EQ(mb.started_s, ma.started_s);
  EXPECT_EQ(mb.ended_s, ma.ended_s);
  const auto va = *a.vehicles().get(kVehicle);
  const auto vb = *b.vehicles().get(kVehicle);
  EXPECT_EQ(vb.kind, va.kind);
  EXPECT_EQ(vb.max_speed_mps, va.max_speed_mps);
  EXPECT_EQ(vb.length_m, va.length_m);

  const auto nav = a.navigation().for_mission(mission_);
  ASSERT_GT(nav.size(), 100u);
  EXPECT_EQ(b.navigation().for_mission(id), nav);  // doubles compared exactly
  EXPECT_EQ(imported->nav_samples, nav.size());

  const auto ea = events_of(a, mission_);
  const auto eb = events_of(b, id);
  ASSERT_EQ(eb.size(), ea.size());
  ASSERT_GT(ea.size(), 0u);
  for (std::size_t i = 0; i < ea.size(); ++i) {
    EXPECT_EQ(eb[i].t_s, ea[i].t_s) << i;
    EXPECT_EQ(eb[i].kind, ea[i].kind) << i;
    EXPECT_EQ(eb[i].message, ea[i].message) << i;
  }
  EXPECT_EQ(b.missions().condition_sets(id), a.missions().condition_sets(mission_));
  EXPECT_FALSE(a.missions().condition_sets(mission_).empty());

  const auto ta = turns_of(a, mission_);
  const auto tb = turns_of(b, id);
  ASSERT_EQ(tb.size(), ta.size());
  ASSERT_GE(ta.size(), 8u);
  for (std::size_t i = 0; i < ta.size(); ++i) {
    SCOPED_TRACE("turn " + std::to_string(ta[i].id));
    expect_same_row(tb[i], ta[i]);
    const auto sa = *a.turns().get(ta[i].id);
    const auto sb = *b.turns().get(tb[i].id);
    EXPECT_TRUE(sb.raw == sa.raw);
    ASSERT_EQ(sb.normalized.has_value(), sa.normalized.has_value());
    if (sa.normalized) {
      EXPECT_TRUE(*sb.normalized == *sa.normalized);
    }
  }

  const auto ca = *a.currents().for_mission(mission_);
  const auto cb = b.currents().for_mission(id);
  ASSERT_TRUE(cb);
  EXPECT_EQ(cb->t_s, ca.t_s);
  EXPECT_EQ(cb->method, ca.method);
  EXPECT_EQ(cb->estimate.east_mps, ca.estimate.east_mps);
  EXPECT_EQ(cb->estimate.north_mps, ca.estimate.north_mps);
  EXPECT_EQ(cb->estimate.covariance, ca.estimate.covariance);
  EXPECT_EQ(cb->estimate.speed_scale, ca.estimate.speed_scale);
  EXPECT_EQ(cb->estimate.residual_rms_mps, ca.estimate.residual_rms_mps);
  EXPECT_EQ(cb->estimate.legs, ca.estimate.legs);
  ASSERT_TRUE(ca.speed_reference && ca.drift_scatter);
  EXPECT_EQ(cb->speed_reference, ca.speed_reference);
  EXPECT_EQ(cb->drift_scatter, ca.drift_scatter);
  // What the table is built from: the turns in the water frame.
  const auto wa = a.turns().load_normalized({mission_}, std::nullopt, false,
                                            store::TurnFrameChoice::water_where_known);
  const auto wb = b.turns().load_normalized({id}, std::nullopt, false,
                                            store::TurnFrameChoice::water_where_known);
  ASSERT_EQ(wb.size(), wa.size());
  for (std::size_t i = 0; i < wa.size(); ++i) {
    EXPECT_TRUE(wa[i].meta().removed_current.has_value());
    EXPECT_TRUE(wb[i] == wa[i]) << i;
  }
}

TEST_F(MissionMcapTest, MessagesAreInLogTimeOrderWithOneChannelPerKind) {
  const app::McapExport e = exported();
  const auto c = app::mcap::read_mcap(e.bytes);
  ASSERT_FALSE(c.messages.empty());
  for (std::size_t i = 1; i < c.messages.size(); ++i)
    ASSERT_LE(c.messages[i - 1].log_time_ns, c.messages[i].log_time_ns) << "message " << i;
  ASSERT_TRUE(c.statistics);
  EXPECT_EQ(c.statistics->message_count, c.messages.size());
  EXPECT_GE(c.chunk_count, 1u);
  EXPECT_EQ(c.library.rfind("avk-station", 0), 0u) << c.library;

  store::Store& db = app::store_of(*ctx_);
  using K = app::foxglove::ChannelKind;
  const auto nav = db.navigation().for_mission(mission_).size();
  const auto turns = turns_of(db, mission_).size();
  EXPECT_EQ(e.messages.of(topic(K::pose)), nav);
  EXPECT_EQ(e.messages.of(topic(K::transform)), nav);
  EXPECT_EQ(e.messages.of(topic(K::navigation)), nav);
  EXPECT_EQ(e.messages.of(topic(K::turn)), turns);
  EXPECT_EQ(e.messages.of(topic(K::turn_record)), turns);
  EXPECT_EQ(e.messages.of(topic(K::region)), 1u);
  EXPECT_EQ(e.messages.of(topic(K::log)), events_of(db, mission_).size());
  EXPECT_EQ(e.messages.total(), c.messages.size());
  // The channels advertise the live connection's schemas.
  for (const auto& ch : c.channels) {
    const auto kind = app::foxglove::channel_kind_of(ch.topic, kVehicle);
    ASSERT_TRUE(kind) << ch.topic;
    const auto spec = app::foxglove::channel_spec(kVehicle, *kind);
    bool found = false;
    for (const auto& s : c.schemas)
      if (s.id == ch.schema_id) {
        found = true;
        EXPECT_EQ(s.name, spec.schema_name);
        EXPECT_EQ(s.data, spec.schema);
        EXPECT_EQ(s.encoding, "jsonschema");
      }
    EXPECT_TRUE(found) << ch.topic;
    EXPECT_EQ(ch.message_encoding, "json");
  }
  // A measured turn shows the table's and the instantaneous prediction; no model was fitted.
  const auto turn_channel = channel_id(c, K::turn);
  bool checked = false;
  for (const auto& m : c.messages) {
    if (m.channel_id != turn_channel) continue;
    const json j = json::parse(m.data);
    std::vector<std::string> ids;
    for (const auto& entity : j["entities"])
      ids.push_back(entity["id"]);
    EXPECT_NE(std::find(ids.begin(), ids.end(), "turn/avk"), ids.end()) << m.data.substr(0, 200);
    EXPECT_NE(std::find(ids.begin(), ids.end(), "turn/instantaneous"), ids.end());
    EXPECT_NE(std::find(ids.begin(), ids.end(), "turn/measured"), ids.end());
    EXPECT_EQ(std::find(ids.begin(), ids.end(), "turn/model"), ids.end());
    checked = true;
    break;
  }
  EXPECT_TRUE(checked);
}

TEST_F(MissionMcapTest, LocationIsWrittenOnlyWithADatum) {
  using K = app::foxglove::ChannelKind;
  const auto without = app::mcap::read_mcap(exported().bytes);
  for (const auto& ch : without.channels)
    EXPECT_NE(ch.topic, topic(K::location));

  app::McapExportOptions o;
  o.datum = vehicle::LatLon{47.6, -122.3};
  o.compression = app::mcap::Compression::none;
  const auto with = exported(o);
  const auto nav = app::store_of(*ctx_).navigation().for_mission(mission_);
  EXPECT_EQ(with.messages.of(topic(K::location)), nav.size());
  const auto c = app::mcap::read_mcap(with.bytes);
  const auto location = channel_id(c, K::location);
  for (const auto& m : c.messages)
    if (m.channel_id == location) {
      const json j = json::parse(m.data);
      // Within the 200 m region of the datum: a few thousandths of a degree.
      EXPECT_NEAR(j["latitude"].get<double>(), 47.6, 0.01);
      EXPECT_NEAR(j["longitude"].get<double>(), -122.3, 0.01);
      break;
    }

  o.datum = vehicle::LatLon{95.0, 0.0};
  const auto bad = app::export_mission_mcap(*ctx_, mission_, o);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, app::ErrorCode::invalid_argument);
  EXPECT_EQ(bad.error().field, "datum");
}

TEST_F(MissionMcapTest, AnUnknownMissionIsNotFound) {
  const auto r = app::export_mission_mcap(*ctx_, 9999);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, app::ErrorCode::not_found);
}

TEST_F(MissionMcapTest, ACorruptFileLeavesTheDatabaseExactlyAsItWas) {
  const std::string good = exported().bytes;
  avk::testing::TempDb target("avk_mcap_corrupt");
  app::Context to(target.path());
  ASSERT_TRUE(app::import_mission_mcap(to, good));  // something there already
  const auto before = all_counts(target.path());

  using K = app::foxglove::ChannelKind;
  struct Case {
    std::string name;
    std::function<void(app::mcap::McapContents&)> edit;
    std::string expected;  // in the error message
  };
  const std::vector<Case> cases = {
      {"the last turn record cut short",
       [](app::mcap::McapContents& c) {
         const auto ch = channel_id(c, K::turn_record);
         for (auto it = c.messages.rbegin(); it != c.messages.rend(); ++it)
           if (it->channel_id == ch) {
             it->data.resize(it->data.size() / 2);
             break;
           }
       },
       std::string("on ") + topic(K::turn_record) + ": not a JSON object"},
      {"a navigation sample whose x is text",
       [](app::mcap::McapContents& c) {
         const auto ch = channel_id(c, K::navigation);
         for (auto& m : c.messages)
           if (m.channel_id == ch && m.sequence == 17) {
             json j = json::parse(m.data);
             j["x_m"] = "east";
             m.data = j.dump();
           }
       },
       std::string("message 17 on ") + topic(K::navigation) + ": 'x_m' is not a number"},
      {"a turn whose raw record has no samples member",
       [](app::mcap::McapContents& c) {
         const auto ch = channel_id(c, K::turn_record);
         for (auto& m : c.messages)
           if (m.channel_id == ch) {
             json j = json::parse(m.data);
             j["raw"].erase("samples");
             m.data = j.dump();
             break;
           }
       },
       "'raw' is not a turn record"},
      {"an event missing",
       [](app::mcap::McapContents& c) {
         const auto ch = channel_id(c, K::log);
         for (auto it = c.messages.begin(); it != c.messages.end(); ++it)
           if (it->channel_id == ch) {
             c.messages.erase(it);
             break;
           }
       },
       "events but avk.mission says"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name);
    const auto r = app::import_mission_mcap(to, rewritten(good, k.edit));
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, app::ErrorCode::invalid_argument);
    EXPECT_NE(r.error().message.find(k.expected), std::string::npos) << r.error().message;
    EXPECT_EQ(all_counts(target.path()), before);
  }
  // Bytes damaged inside a chunk: the chunk's CRC says so before any message is looked at.
  std::string damaged = good;
  damaged[damaged.size() / 2] ^= 0x5a;
  const auto r = app::import_mission_mcap(to, damaged);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("not a readable MCAP file"), std::string::npos)
      << r.error().message;
  EXPECT_EQ(all_counts(target.path()), before);
}

// A station-written file whose values are out of the ranges every reader of navigation holds
// (vehicle/nav_ranges.hpp) or whose navigation runs back in time: refused naming the message by
// topic and sequence, and nothing stored.
TEST_F(MissionMcapTest, OutOfRangeValuesAndTimeGoingBackAreRefusedNamingTheMessage) {
  const std::string good = exported().bytes;
  avk::testing::TempDb target("avk_mcap_ranges");
  app::Context to(target.path());
  (void)app::store_of(to);  // the schema, for the counts
  const auto before = all_counts(target.path());

  using K = app::foxglove::ChannelKind;
  // Sets `key` of the message of `kind` with `sequence` to what `value` gives from the message
  // before it on that channel (null before the first) and the message itself.
  const auto set = [](K kind, std::uint32_t sequence, const char* key,
                      std::function<json(const json* previous, const json& self)> value) {
    return [=](app::mcap::McapContents& c) {
      const auto ch = channel_id(c, kind);
      std::optional<json> previous;
      for (auto& m : c.messages) {
        if (m.channel_id != ch) continue;
        json j = json::parse(m.data);
        if (m.sequence == sequence) {
          j[key] = value(previous ? &*previous : nullptr, j);
          m.data = j.dump();
          return;
        }
        previous = std::move(j);
      }
      ADD_FAILURE() << "no message " << sequence << " on " << topic(kind);
    };
  };
  const auto constant = [](double v) { return [v](const json*, const json&) { return json(v); }; };
  const std::string nav = "message 17 on " + topic(K::navigation) + ": ";
  struct Case {
    std::string name;
    std::function<void(app::mcap::McapContents&)> edit;
    std::string expected;  // in the error message
  };
  const std::vector<Case> cases = {
      {"a time of 1e308 s", set(K::navigation, 17, "t_s", constant(1e308)),
       nav + "'t_s' 1e+308 is out of range [0.0, 10000000000.0]"},
      {"x of -1e308 m", set(K::navigation, 17, "x_m", constant(-1e308)),
       nav + "'x_m' -1e+308 is out of range"},
      {"y of 2e7 m", set(K::navigation, 17, "y_m", constant(2e7)),
       nav + "'y_m' 20000000.0 is out of range"},
      {"a speed of -5 m/s", set(K::navigation, 17, "speed_mps", constant(-5.0)),
       nav + "'speed_mps' -5.0 is out of range [0.0, 100.0]"},
      {"a heading of 400 deg", set(K::navigation, 17, "heading_deg", constant(400.0)),
       nav + "'heading_deg' 400.0 is out of range [0.0, 360.0]"},
      {"a desired speed of 1000 m/s", set(K::navigation, 17, "desired_speed_mps", constant(1e3)),
       nav + "'desired_speed_mps' 1000.0 is out of range [0.0, 100.0]"},
      {"a sample earlier than the one before it",
       set(K::navigation, 17, "t_s",
           [](const json* previous, const json&) {
             return (*previous)["t_s"].get<double>() - 0.5;
           }),
       nav + "'t_s'"},
      {"an event before the clock started", set(K::log, 1, "t_s", constant(-1.0)),
       "message 1 on " + topic(K::log) + ": 't_s' -1.0 is out of range"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name);
    const auto r = app::import_mission_mcap(to, rewritten(good, k.edit));
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, app::ErrorCode::invalid_argument);
    EXPECT_EQ(r.error().field, "file");
    EXPECT_NE(r.error().message.find(k.expected), std::string::npos) << r.error().message;
    EXPECT_EQ(all_counts(target.path()), before);
  }
  // The time going back is named as such.
  const auto back = app::import_mission_mcap(to, rewritten(good, cases[6].edit));
  ASSERT_FALSE(back);
  EXPECT_NE(back.error().message.find("earlier than the navigation sample before it"),
            std::string::npos)
      << back.error().message;
}

TEST_F(MissionMcapTest, AFailureHalfwayThroughTheStoreRollsEverythingBack) {
  const std::string good = exported().bytes;
  avk::testing::TempDb target("avk_mcap_rollback");
  app::Context to(target.path());
  ASSERT_TRUE(app::import_mission_mcap(to, good));
  const auto before = all_counts(target.path());
  {
    // The turns are inserted after the mission, its navigation and its events.
    store::Connection c(target.path());
    c.exec(
        "CREATE TRIGGER refuse_turns BEFORE INSERT ON turns "
        "BEGIN SELECT RAISE(ABORT, 'turns refused by the test'); END");
  }
  EXPECT_THROW((void)app::import_mission_mcap(to, good), store::StoreError);
  EXPECT_EQ(all_counts(target.path()), before);
}

TEST_F(MissionMcapTest, FilesNotWrittenByTheStationAreRefusedWithTheReason) {
  avk::testing::TempDb target("avk_mcap_foreign");
  app::Context to(target.path());
  (void)app::store_of(to);  // the schema, for the count at the end
  const auto refused = [&](const std::string& bytes, const std::string& expected) {
    const auto r = app::import_mission_mcap(to, bytes);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, app::ErrorCode::invalid_argument);
    EXPECT_EQ(r.error().field, "file");
    EXPECT_NE(r.error().message.find(expected), std::string::npos) << r.error().message;
  };
  app::mcap::Writer foreign;
  const auto schema = foreign.add_schema("foxglove.Log", "jsonschema", "{}");
  const auto ch = foreign.add_channel(schema, "/rosout", "json");
  foreign.add_message(ch, 1, 1, R"({"message":"hello"})");
  refused(foreign.finish(), "no avk.mission metadata record");
  refused("this is not MCAP at all", "not a readable MCAP file");
  // A zstd bomb: 32 KiB declaring 1 GiB, refused from the declared size.
  namespace mb = avk::testing::mcap_bytes;
  refused(mb::hand_built_file(mb::zero_chunk(std::uint64_t{9} * 119'304'647)),
          "not a readable MCAP file: chunk at offset 29: uncompressed_size 1073741823 is more than "
          "a chunk may hold");

  const std::string good = exported().bytes;
  refused(rewritten(good,
                    [](app::mcap::McapContents& c) {
                      for (auto& m : c.metadata)
                        if (m.name == "avk.mission")
                          m.entries.insert_or_assign("avk_mcap_version", std::string(1, '2'));
                    }),
          "avk_mcap_version '2'");
  refused(rewritten(good,
                    [](app::mcap::McapContents& c) {
                      std::erase_if(c.metadata,
                                    [](const auto& m) { return m.name == "avk.vehicle"; });
                    }),
          "no avk.vehicle metadata record");
  EXPECT_EQ(count_rows(target.path(), "missions"), 0);
}

// Regression: a mission's name had no limit (a 900 kB one was stored and listed). An imported
// recording's free text is bounded like the station's own input, naming the record and field.
TEST_F(MissionMcapTest, FreeTextTooLongIsRefusedNamingTheRecordAndTheLimit) {
  avk::testing::TempDb target("avk_mcap_text");
  app::Context to(target.path());
  (void)app::store_of(to);
  const std::string good = exported().bytes;
  const auto with_entry = [&](const char* record, const char* key, std::string value) {
    return rewritten(good, [&](app::mcap::McapContents& c) {
      for (auto& m : c.metadata)
        if (m.name == record) m.entries.insert_or_assign(key, value);
    });
  };
  struct Case {
    std::string bytes;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {with_entry("avk.mission", "name", std::string(900000, 'n')),
       "avk.mission metadata 'name' must be at most 256 bytes (UTF-8), got 900000"},
      {with_entry("avk.mission", "status_reason", std::string(5000, 'r')),
       "avk.mission metadata 'status_reason' must be at most 1024 bytes"},
      {with_entry("avk.vehicle", "kind", std::string(100, 'k')),
       "avk.vehicle metadata 'kind' must be at most 64 bytes"},
      {rewritten(good,
                 [](app::mcap::McapContents& c) {
                   const auto ch = channel_id(c, app::foxglove::ChannelKind::log);
                   for (auto& m : c.messages)
                     if (m.channel_id == ch) {
                       json j = json::parse(m.data);
                       j["message"] = std::string(5000, 'm');
                       m.data = j.dump();
                       break;
                     }
                 }),
       "event 0 of the log channel: 'message' must be at most 4096 bytes"},
  };
  for (const auto& k : cases) {
    const auto r = app::import_mission_mcap(to, k.bytes);
    ASSERT_FALSE(r) << k.expected;
    EXPECT_EQ(r.error().field, "file");
    EXPECT_NE(r.error().message.find(k.expected), std::string::npos) << r.error().message;
  }
  EXPECT_EQ(count_rows(target.path(), "missions"), 0);
  EXPECT_EQ(count_rows(target.path(), "vehicles"), 0);
}

}  // namespace
