#include "daemon/recording/recording_reader.hpp"

#include <cmath>

#include "common/mcap/fsd_profile.hpp"

namespace fsd {

RecordingReader::RecordingReader(std::span<const std::uint8_t> file, mcap::ReaderOptions options)
    : reader_(file, options) {
  while (auto r = reader_.next()) {
    if (auto* m = std::get_if<mcap::Message>(&r->record)) {
      first_message_ = std::move(*m);
      break;
    }
    take(r->record);
  }
  if (const auto why = mcap::recording_version_problem(metadata_)) throw RecordingError(*why);
  if (!metadata(mcap::kConfigMetadata) || !metadata(mcap::kRunMetadata))
    throw RecordingError("not a recording of fsd run (no " + std::string(mcap::kConfigMetadata) + " and " +
                         std::string(mcap::kRunMetadata) + " metadata before its first message)");
}

const mcap::StringMap* RecordingReader::metadata(std::string_view name) const {
  for (const auto& m : metadata_)
    if (m.name == name) return &m.metadata;
  return nullptr;
}

std::optional<std::string> RecordingReader::attachment(std::string_view name) const {
  for (const auto& a : attachments_)
    if (a.name == name) return std::string(a.data.begin(), a.data.end());
  return std::nullopt;
}

void RecordingReader::take(const mcap::Record& r) {
  if (const auto* m = std::get_if<mcap::Metadata>(&r)) {
    if (metadata_.size() < 64) metadata_.push_back(*m);
  } else if (const auto* a = std::get_if<mcap::Attachment>(&r)) {
    if (attachments_.size() < 16) attachments_.push_back(*a);
  } else if (const auto* c = std::get_if<mcap::Channel>(&r)) {
    ChannelUse u;
    if (c->message_encoding == mcap::kRawEncoding) {
      if (c->topic == kCycleTopic)
        u.use = Use::Cycle;
      else if (c->topic == kCommandTopic)
        u.use = Use::Command;
      else if (const auto raw = raw_channel_of_topic(c->topic))
        u = {Use::Raw, *raw};
    }
    channels_.emplace(c->id, u);  // a repeated channel record (the summary) keeps the first
  }
}

void RecordingReader::flush_frames(const CycleMarker* marker) {
  const bool exact = marker && marker->frame_times.size() == held_.size();
  for (std::size_t i = 0; i < held_.size(); ++i) {
    if (exact)
      held_[i].t = marker->frame_times[i];
    else
      ++counters_.inexact_frames;
    ready_.push_back(std::move(held_[i]));
  }
  held_.clear();
}

bool RecordingReader::take_message(mcap::Message&& m) {
  const auto it = channels_.find(m.channel_id);
  if (it == channels_.end()) {
    ++counters_.bad_messages;
    return false;
  }
  const Stamp t_ns = static_cast<double>(m.log_time) / 1e9;
  switch (it->second.use) {
    case Use::Raw: {
      held_.push_back({RecordingEvent::Kind::Frame, it->second.raw, t_ns, std::move(m.data)});
      ++counters_.frames;
      if (held_.size() > kMaxCycleFrames) flush_frames(nullptr);  // no marker in sight: do not hold the file
      return !ready_.empty();
    }
    case Use::Cycle: {
      const auto marker = decode_cycle(m.data);
      if (!marker) {
        ++counters_.bad_messages;
        return false;
      }
      flush_frames(&*marker);
      ready_.push_back({RecordingEvent::Kind::Cycle, RawChannel::Nmea, marker->now, {}});
      ++counters_.cycles;
      return true;
    }
    case Use::Command: {
      const auto c = decode_command(m.data);
      if (!c) {
        ++counters_.bad_messages;
        return false;
      }
      // Frames after a cycle's marker and before its command cannot be (the Stack's step takes none), but a
      // damaged file may hold them: they keep their order before the command.
      flush_frames(nullptr);
      ready_.push_back({RecordingEvent::Kind::Command, RawChannel::Nmea, c->now, std::move(m.data)});
      ++counters_.commands;
      return true;
    }
    case Use::Other:
      ++counters_.other_messages;
      return false;
  }
  return false;
}

std::optional<RecordingEvent> RecordingReader::next() {
  while (ready_.empty() && !done_) {
    if (first_message_) {
      auto m = std::move(*first_message_);
      first_message_.reset();
      take_message(std::move(m));
      continue;
    }
    auto r = reader_.next();
    if (!r) {
      done_ = true;
      flush_frames(nullptr);
      break;
    }
    if (auto* m = std::get_if<mcap::Message>(&r->record))
      take_message(std::move(*m));
    else
      take(r->record);
  }
  if (ready_.empty()) return std::nullopt;
  RecordingEvent e = std::move(ready_.front());
  ready_.pop_front();
  return e;
}

}  // namespace fsd
