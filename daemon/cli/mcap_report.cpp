#include "daemon/cli/mcap_report.hpp"

#include <cstdio>
#include <sstream>

#include "common/mcap/fsd_profile.hpp"

namespace fsd {
namespace {

std::string seconds(mcap::Timestamp ns) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(ns) * 1e-9);
  return buf;
}

std::string compression_name(const std::string& c) { return c.empty() ? "none" : c; }

std::string status_line(const mcap::FileInfo& info) {
  if (info.complete) return "complete";
  if (info.truncated_at)
    return "cut off at offset " + std::to_string(*info.truncated_at) + " of " + std::to_string(info.file_size) +
           " bytes: read up to there by a linear scan";
  return "incomplete";
}

}  // namespace

std::string format_mcap_info(const std::string& file, const mcap::FileInfo& info) {
  std::ostringstream o;
  o << "file:        " << file << " (" << info.file_size << " bytes)\n";
  o << "profile:     " << (info.header.profile.empty() ? "(none)" : info.header.profile) << "\n";
  o << "library:     " << (info.header.library.empty() ? "(none)" : info.header.library) << "\n";
  if (info.start_time) {
    o << "messages:    " << info.messages << " from " << seconds(*info.start_time) << " s to "
      << seconds(*info.end_time) << " s (" << seconds(*info.end_time - *info.start_time) << " s)\n";
  } else {
    o << "messages:    0\n";
  }
  o << "channels:    " << info.channels.size() << "\n";
  if (!info.channels.empty()) {
    std::size_t topic_w = 5, enc_w = 8;
    for (const auto& c : info.channels) {
      topic_w = std::max(topic_w, c.topic.size());
      enc_w = std::max(enc_w, c.message_encoding.size());
    }
    char buf[512];
    std::snprintf(buf, sizeof buf, "  %5s  %-*s  %-*s  %10s  %s\n", "id", int(topic_w), "topic", int(enc_w), "encoding",
                  "messages", "schema");
    o << buf;
    for (const auto& c : info.channels) {
      std::snprintf(buf, sizeof buf, "  %5u  %-*s  %-*s  %10llu  %s\n", unsigned(c.id), int(topic_w), c.topic.c_str(),
                    int(enc_w), c.message_encoding.c_str(), static_cast<unsigned long long>(c.messages),
                    c.schema_name.empty() ? "(none)" : c.schema_name.c_str());
      o << buf;
    }
  }
  o << "chunks:      " << info.chunks;
  if (!info.chunk_compressions.empty()) {
    o << " (";
    bool first = true;
    for (const auto& [c, n] : info.chunk_compressions) {
      o << (first ? "" : ", ") << compression_name(c) << " " << n;
      first = false;
    }
    o << ")";
  }
  if (info.chunks_damaged) o << ", " << info.chunks_damaged << " damaged and skipped";
  o << "\n";
  o << "metadata:    " << (info.metadata.empty() ? std::string("none") : std::to_string(info.metadata.size())) << "\n";
  for (const auto& m : info.metadata) {
    o << "  " << m.name;
    // The recorder's counters and the recording version are short: print them; a configuration is not.
    if (m.name == mcap::kRecorderMetadata || m.name == mcap::kRecordingMetadata) {
      for (const auto& [k, v] : m.metadata) o << "  " << k << "=" << v;
    } else {
      o << "  (" << m.metadata.size() << " keys)";
    }
    o << "\n";
  }
  o << "attachments: " << (info.attachments.empty() ? std::string("none") : std::to_string(info.attachments.size()))
    << "\n";
  for (const auto& a : info.attachments)
    o << "  " << a.name << "  " << (a.media_type.empty() ? "(no media type)" : a.media_type) << "  " << a.size
      << " bytes\n";
  o << "summary:     " << (info.summary_present ? "present" : "absent (" + info.summary_problem + ")") << "\n";
  o << "status:      " << status_line(info) << "\n";
  for (const auto& i : info.issues) o << "  " << i.what << "\n";
  return o.str();
}

nlohmann::json mcap_info_json(const std::string& file, const mcap::FileInfo& info) {
  using nlohmann::json;
  json j = {{"file", file},
            {"file_size", info.file_size},
            {"profile", info.header.profile},
            {"library", info.header.library},
            {"messages", info.messages},
            {"chunks", info.chunks},
            {"chunks_damaged", info.chunks_damaged},
            {"summary_present", info.summary_present},
            {"complete", info.complete}};
  j["start_s"] = info.start_time ? json(static_cast<double>(*info.start_time) * 1e-9) : json(nullptr);
  j["end_s"] = info.end_time ? json(static_cast<double>(*info.end_time) * 1e-9) : json(nullptr);
  j["duration_s"] =
      info.start_time ? json(static_cast<double>(*info.end_time - *info.start_time) * 1e-9) : json(nullptr);
  j["start_ns"] = info.start_time ? json(*info.start_time) : json(nullptr);
  j["end_ns"] = info.end_time ? json(*info.end_time) : json(nullptr);
  j["channels"] = json::array();
  for (const auto& c : info.channels)
    j["channels"].push_back({{"id", c.id},
                             {"topic", c.topic},
                             {"message_encoding", c.message_encoding},
                             {"schema", c.schema_name},
                             {"messages", c.messages}});
  j["chunk_compression"] = json::object();
  for (const auto& [c, n] : info.chunk_compressions) j["chunk_compression"][compression_name(c)] = n;
  j["metadata"] = json::array();
  for (const auto& m : info.metadata) j["metadata"].push_back({{"name", m.name}, {"values", m.metadata}});
  j["attachments"] = json::array();
  for (const auto& a : info.attachments)
    j["attachments"].push_back({{"name", a.name}, {"media_type", a.media_type}, {"size", a.size}});
  if (!info.summary_present) j["summary_problem"] = info.summary_problem;
  j["truncated_at"] = info.truncated_at ? json(*info.truncated_at) : json(nullptr);
  j["issues"] = json::array();
  for (const auto& i : info.issues)
    j["issues"].push_back({{"kind", mcap::to_string(i.kind)}, {"offset", i.offset}, {"what", i.what}});
  return j;
}

std::string format_recover_report(const std::string& in, const std::string& out, const mcap::RecoverReport& r) {
  std::ostringstream o;
  o << "recovered " << in << " into " << out << "\n";
  o << "kept: " << r.messages << " messages on " << r.channels << " channels (" << r.schemas << " schemas), "
    << r.metadata << " metadata records, " << r.attachments << " attachments, from " << r.chunks_read
    << " intact chunks\n";
  o << "lost: ";
  std::vector<std::string> lost;
  if (r.chunks_lost) lost.push_back(std::to_string(r.chunks_lost) + " damaged chunks");
  if (r.bytes_lost) lost.push_back(std::to_string(r.bytes_lost) + " bytes at the cut-off end");
  if (r.messages_without_channel)
    lost.push_back(std::to_string(r.messages_without_channel) + " messages whose channel record was lost");
  if (lost.empty()) lost.push_back("nothing");
  for (std::size_t i = 0; i < lost.size(); ++i) o << (i ? ", " : "") << lost[i];
  o << "\n";
  if (r.channels_without_schema) o << "note: " << r.channels_without_schema << " channels lost their schema\n";
  for (const auto& i : r.issues) o << "  " << i.what << "\n";
  return o.str();
}

}  // namespace fsd
