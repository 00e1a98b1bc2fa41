#include "daemon/recording/recorder.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/bounded_queue.hpp"
#include "common/logging.hpp"
#include "common/mcap/byte_io.hpp"
#include "common/mcap/fsd_profile.hpp"
#include "common/mcap/writer.hpp"
#include "daemon/recording/derived_channels.hpp"
#include "web/metrics.hpp"

namespace fsd {

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

// One thing the Stack did, on its way to the writer thread.
struct Item {
  enum class Kind : std::uint8_t { Frame, Cycle, Output, Snapshot, Json } kind = Kind::Frame;
  RawChannel channel = RawChannel::Nmea;
  Stamp t = 0;
  std::vector<std::uint8_t> bytes;                      // the frame's, or the encoded command
  std::shared_ptr<const TelemetrySnapshot> snapshot{};  // Snapshot: turned into derived messages by the writer
  std::string topic{}, json{};                          // Json: one message of a derived channel
};

constexpr std::size_t kLogQueue = 1024;  // log lines between the logging threads and the writer

}  // namespace

const ConfigSection<RecordSettings>& record_section() {
  static const auto s =
      ConfigSection<RecordSettings>("record")
          .number("split_mb", &RecordSettings::split_mb, 0.01, 1048576.0, "MiB",
                  "fsd run --record: a new file (run-001.mcap, ...) once the current one's messages reach this "
                  "size (the open chunk counted uncompressed), after a whole cycle; each part carries the "
                  "configuration and replays alone.")
          .integer("queue_frames", &RecordSettings::queue_frames, 16, 1 << 22, "",
                   "fsd run --record: frames, cycle markers and commands queued between the control thread and "
                   "the recorder's writer; when full the oldest is dropped and counted (never waits on the disk).");
  return s;
}

nlohmann::json to_json(const RecorderStats& s) {
  return {{"files", s.files},
          {"frames_written", s.frames_written},
          {"cycles_written", s.cycles_written},
          {"commands_written", s.commands_written},
          {"derived_written", s.derived_written},
          {"log_dropped", s.log_dropped},
          {"dropped", s.dropped},
          {"bytes", s.bytes},
          {"queue_high_water", s.queue_high_water},
          {"error", s.error}};
}

std::string recording_part_path(const std::string& first, int part) {
  if (part == 0) return first;
  const std::filesystem::path p(first);
  char n[16];
  std::snprintf(n, sizeof n, "-%03d", part);
  return (p.parent_path() / (p.stem().string() + n + p.extension().string())).string();
}

struct Recorder::Impl {
  std::string path;
  RecordSettings settings;
  mcap::StringMap config, run;
  std::optional<std::string> track_csv;
  std::shared_ptr<spdlog::logger> log = logger("record");

  BoundedQueue<Item> queue;
  BoundedQueue<Item> log_queue{kLogQueue};  // log lines, from any thread
  std::atomic<Stamp> last_cycle{0};         // the run's clock for the log lines
  DerivedChannels derived;
  std::map<std::string, web::ChannelSpec> derived_specs;
  bool lossless = false;
  std::atomic<bool> closing{false};
  std::atomic<bool> failed_flag{false};   // the writer stopped on an error: nothing to wait for
  std::atomic<std::uint64_t> refused{0};  // pushed after the recording stopped
  std::thread thread;
  std::once_flag closed;

  // The writer thread's. The current part:
  int part = 0;
  std::unique_ptr<mcap::FileSink> sink;
  std::unique_ptr<mcap::Writer> writer;
  std::map<RawChannel, std::uint16_t> raw_ids;
  std::map<std::string, std::uint16_t> json_ids, json_schema_ids;  // by topic, by schema name and text
  std::uint16_t cycle_id = 0, command_id = 0;
  std::vector<Stamp> since_marker;  // exact times of the frames written since the last cycle marker
  std::uint64_t bytes_done = 0;     // of the finished parts
  std::uint64_t part_head = 0;      // the current part's bytes before its first message (metadata, track)
  bool failed = false;

  std::mutex closing_m;
  std::map<std::string, mcap::StringMap> closing_metadata;  // guarded by closing_m

  mutable std::mutex stats_m;
  RecorderStats st;  // guarded by stats_m

  struct Gauges {
    web::Gauge &frames, &dropped, &bytes, &files, &stopped;
  };
  std::unique_ptr<Gauges> gauges_owned;
  std::atomic<Gauges*> gauges{nullptr};  // set once by set_metrics, read by the writer thread

  void publish() {
    Gauges* g = gauges.load(std::memory_order_acquire);
    if (!g) return;
    const RecorderStats s = stats();
    g->frames.set(static_cast<double>(s.frames_written));
    g->dropped.set(static_cast<double>(s.dropped));
    g->bytes.set(static_cast<double>(s.bytes));
    g->files.set(static_cast<double>(s.files.size()));
    g->stopped.set(s.error.empty() ? 0.0 : 1.0);
  }

  Impl(std::string p, RecordSettings s, const RecordingContents& c, bool lossless_)
      : path(std::move(p)),
        settings(s),
        run(to_metadata(c.run)),
        queue(static_cast<std::size_t>(s.queue_frames)),
        derived(c.car),
        lossless(lossless_) {
    for (auto& spec : derived_channel_specs()) derived_specs.emplace(spec.topic, std::move(spec));
    if (c.config) config = flatten_config(*c.config);
    if (!c.track_file.empty()) {
      // The bytes the run's track was parsed from: the replay parses the very same (a reformatted copy would round).
      std::ifstream f(c.track_file, std::ios::binary);
      std::ostringstream text;
      text << f.rdbuf();
      if (!f) throw std::invalid_argument("--record: cannot read the track file " + c.track_file);
      track_csv = text.str();
    }
    try {
      open_part();
    } catch (const mcap::McapError& e) {
      throw std::invalid_argument("--record " + path + ": " + e.what());
    }
    thread = std::thread([this] { write_loop(); });
  }

  void push(Item&& item) {
    // One producer (the Stack's thread): only the writer changes the size meanwhile, and only downwards.
    while (lossless && queue.size() >= queue.capacity() && !failed_flag.load(std::memory_order_relaxed))
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    if (!queue.push(std::move(item)) && closing.load(std::memory_order_relaxed)) refused.fetch_add(1);
  }

  void open_part() {
    const std::string file = recording_part_path(path, part);
    sink = std::make_unique<mcap::FileSink>(file);
    writer = std::make_unique<mcap::Writer>(*sink);
    raw_ids.clear();
    json_ids.clear();
    json_schema_ids.clear();
    cycle_id = command_id = 0;
    writer->write_metadata(std::string(mcap::kRecordingMetadata), mcap::recording_metadata());
    writer->write_metadata(std::string(mcap::kConfigMetadata), config);
    writer->write_metadata(std::string(mcap::kRunMetadata), run);
    if (track_csv) {
      mcap::Attachment a;
      a.name = std::string(kTrackAttachment);
      a.media_type = "text/csv";
      a.data.assign(track_csv->begin(), track_csv->end());
      writer->write_attachment(a);
    }
    part_head = writer->bytes_written();
    std::lock_guard lock(stats_m);
    st.files.push_back(file);
  }

  // The counters of the file, then its summary.
  void finish_part() {
    const RecorderStats s = stats();
    writer->write_metadata(std::string(mcap::kRecorderMetadata),
                           {{"frames_written", std::to_string(s.frames_written)},
                            {"cycles_written", std::to_string(s.cycles_written)},
                            {"commands_written", std::to_string(s.commands_written)},
                            {"derived_written", std::to_string(s.derived_written)},
                            {"log_dropped", std::to_string(s.log_dropped)},
                            {"dropped", std::to_string(s.dropped)},
                            {"queue_high_water", std::to_string(s.queue_high_water)},
                            {"part", std::to_string(part)}});
    writer->close();
    sink->close();
    bytes_done += writer->bytes_written();
    writer.reset();
    sink.reset();
    std::lock_guard lock(stats_m);
    st.bytes = bytes_done;
  }

  std::uint16_t channel(RawChannel c) {
    if (auto it = raw_ids.find(c); it != raw_ids.end()) return it->second;
    const std::string desc = raw_schema_description(c);
    const auto schema = writer->add_schema(std::string(raw_schema(c)), std::string(mcap::kRawEncoding),
                                           {reinterpret_cast<const std::uint8_t*>(desc.data()), desc.size()});
    const auto id = writer->add_channel(raw_topic(c), std::string(mcap::kRawEncoding), schema);
    raw_ids[c] = id;
    return id;
  }

  std::uint16_t own_channel(std::uint16_t& id, std::string_view topic, std::string_view schema, const char* desc) {
    if (id) return id;
    const std::string d(desc);
    const auto s = writer->add_schema(std::string(schema), std::string(mcap::kRawEncoding),
                                      {reinterpret_cast<const std::uint8_t*>(d.data()), d.size()});
    id = writer->add_channel(std::string(topic), std::string(mcap::kRawEncoding), s);
    return id;
  }

  std::uint16_t json_channel(const std::string& topic) {
    if (auto it = json_ids.find(topic); it != json_ids.end()) return it->second;
    const web::ChannelSpec& spec = derived_specs.at(topic);
    auto [schema_it, fresh] = json_schema_ids.emplace(spec.schema_name + '\n' + spec.schema, 0);
    if (fresh)
      schema_it->second =
          writer->add_schema(spec.schema_name, "jsonschema",
                             {reinterpret_cast<const std::uint8_t*>(spec.schema.data()), spec.schema.size()});
    const auto schema = schema_it->second;
    const auto id = writer->add_channel(topic, "json", schema);
    json_ids[topic] = id;
    return id;
  }

  void write_json(const std::string& topic, Stamp t, const std::string& json) {
    const auto ns = to_ns(t);
    writer->write_message(json_channel(topic), ns, ns,
                          {reinterpret_cast<const std::uint8_t*>(json.data()), json.size()});
    std::lock_guard lock(stats_m);
    ++st.derived_written;
  }

  void write(const Item& item) {
    const auto ns = to_ns(item.t);
    switch (item.kind) {
      case Item::Kind::Snapshot:
        for (const auto& m : derived.messages(*item.snapshot)) write_json(m.topic, m.t, m.payload);
        break;
      case Item::Kind::Json:
        write_json(item.topic, item.t, item.json);
        break;
      case Item::Kind::Frame: {
        writer->write_message(channel(item.channel), ns, ns, item.bytes);
        since_marker.push_back(item.t);
        std::lock_guard lock(stats_m);
        ++st.frames_written;
        break;
      }
      case Item::Kind::Cycle: {
        const auto bytes = encode_cycle({item.t, since_marker});
        since_marker.clear();
        writer->write_message(own_channel(cycle_id, kCycleTopic, kCycleSchema,
                                          "u8 version 1, f64 now, u32 n, n x f64 the frames' exact receive times"),
                              ns, ns, bytes);
        std::lock_guard lock(stats_m);
        ++st.cycles_written;
        break;
      }
      case Item::Kind::Output: {
        writer->write_message(own_channel(command_id, kCommandTopic, kCommandSchema,
                                          "u8 version 1, f64 now, f64 stamp, f64 steering rad, f64 target speed "
                                          "m/s, u8 brake_hard, u8 AS request"),
                              ns, ns, item.bytes);
        std::lock_guard lock(stats_m);
        ++st.commands_written;
        break;
      }
    }
    {
      std::lock_guard lock(stats_m);
      st.bytes = bytes_done + writer->bytes_written();
    }
    // The messages' bytes in this part (compressed as far as written, the open chunk uncompressed).
    const double size = static_cast<double>(writer->bytes_written() + writer->bytes_pending() - part_head);
    const bool cycle_done = item.kind == Item::Kind::Output;
    if ((cycle_done && size >= settings.split_mb * kMiB) || size >= 2 * settings.split_mb * kMiB) {
      finish_part();
      ++part;
      open_part();
    }
  }

  void fail(const std::string& why) {
    failed = true;
    failed_flag = true;
    log->error("recording stopped: {} (the run goes on; {} frames recorded)", why, stats().frames_written);
    std::lock_guard lock(stats_m);
    st.error = why;
  }

  // Writes one item; a write error stops the recording (fail) and drops the file's writer. False once stopped.
  bool write_or_stop(const Item& item) {
    if (failed) return false;
    try {
      write(item);
      return true;
    } catch (const std::exception& e) {
      fail(e.what());
      writer.reset();  // its destructor swallows the sink's errors
      sink.reset();
      return false;
    }
  }

  void write_loop() {
    while (true) {
      // The log lines first: they wait at most one pop of the main queue (100 ms).
      while (auto line = log_queue.try_pop()) write_or_stop(*line);
      auto item = queue.pop_for(std::chrono::milliseconds(100));
      if (!item) {
        if (closing.load() && queue.size() == 0) break;
        continue;
      }
      {
        // The item just taken and those behind it; the producer may refill the slot meanwhile, and a queue never
        // holds more than its capacity.
        const std::uint64_t depth = std::min<std::uint64_t>(queue.size() + 1, queue.capacity());
        std::lock_guard lock(stats_m);
        st.queue_high_water = std::max(st.queue_high_water, depth);
      }
      if (failed) {
        refused.fetch_add(1);
        continue;
      }
      if (write_or_stop(*item) && item->kind == Item::Kind::Output) publish();  // once a cycle
    }
    if (!failed && writer) {
      try {
        while (auto line = log_queue.try_pop()) write(*line);
        {
          std::lock_guard lock(closing_m);
          for (const auto& [name, values] : closing_metadata) writer->write_metadata(name, values);
        }
        finish_part();
      } catch (const std::exception& e) {
        fail(e.what());
      }
    }
    publish();
  }

  void close() {
    std::call_once(closed, [this] {
      closing = true;
      queue.close();
      thread.join();
      const RecorderStats s = stats();
      log->info("recorded {} frames, {} cycles in {} file(s), {:.1f} MiB, {} dropped{}", s.frames_written,
                s.cycles_written, s.files.size(), static_cast<double>(s.bytes) / kMiB, s.dropped,
                s.error.empty() ? "" : " (stopped early: " + s.error + ")");
    });
  }

  RecorderStats stats() const {
    std::lock_guard lock(stats_m);
    RecorderStats s = st;
    s.dropped = queue.dropped() + refused.load();
    s.log_dropped = log_queue.dropped();
    return s;
  }
};

Recorder::Recorder(std::string path, RecordSettings settings, const RecordingContents& contents, bool lossless)
    : impl_(std::make_unique<Impl>(std::move(path), settings, contents, lossless)) {}

Recorder::~Recorder() { close(); }

void Recorder::on_frame(const RawFrame& frame) {
  impl_->push({Item::Kind::Frame, frame.channel, frame.t, {frame.bytes.begin(), frame.bytes.end()}});
}

void Recorder::on_cycle(Stamp now) {
  impl_->last_cycle.store(now, std::memory_order_relaxed);
  impl_->push({Item::Kind::Cycle, RawChannel::Nmea, now, {}});
}

void Recorder::on_output(Stamp now, const ControlCommand& command, wire::vcu::AsRequest request) {
  impl_->push({Item::Kind::Output, RawChannel::Nmea, now, encode_command({now, command, request})});
}

void Recorder::on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& snapshot) {
  if (!snapshot) return;
  Item item;
  item.kind = Item::Kind::Snapshot;
  item.t = snapshot->t;
  item.snapshot = snapshot;
  impl_->push(std::move(item));
}

void Recorder::on_param(Stamp now, const ParamChange& change) {
  Item item;
  item.kind = Item::Kind::Json;
  item.t = now;
  item.topic = kParamChangesTopic;
  ParamChange at_now = change;
  at_now.t = now;  // the run's clock: the cycle that applied it
  item.json = param_change_json(at_now);
  impl_->push(std::move(item));
}

void Recorder::on_log(web::LogLine line) {
  if (impl_->closing.load(std::memory_order_relaxed)) return;
  Item item;
  item.kind = Item::Kind::Json;
  item.t = impl_->last_cycle.load(std::memory_order_relaxed);
  item.topic = web::topics::kLog;
  item.json = web::log_json(item.t, line.level, line.name, line.message);
  impl_->log_queue.push(std::move(item));
}

std::shared_ptr<spdlog::sinks::sink> Recorder::log_sink() {
  return web::make_log_sink([this](web::LogLine line) { on_log(std::move(line)); });
}

void Recorder::add_closing_metadata(const std::string& name, mcap::StringMap values) {
  std::lock_guard lock(impl_->closing_m);
  impl_->closing_metadata[name] = std::move(values);
}

void Recorder::close() { impl_->close(); }

void Recorder::set_metrics(web::Metrics& m) {
  if (impl_->gauges.load()) return;
  impl_->gauges_owned = std::make_unique<Impl::Gauges>(
      Impl::Gauges{m.gauge("fsd_record_frames", "Raw frames written to the recording"),
                   m.gauge("fsd_record_dropped",
                           "Items (frames, cycle markers, commands) the recording lost: queue full or stopped"),
                   m.gauge("fsd_record_bytes", "Bytes written to the recording's files"),
                   m.gauge("fsd_record_files", "Files of the recording (record.split_mb)"),
                   m.gauge("fsd_record_stopped", "1 when a write error stopped the recording")});
  impl_->gauges.store(impl_->gauges_owned.get(), std::memory_order_release);
}

RecorderStats Recorder::stats() const { return impl_->stats(); }

}  // namespace fsd
