#pragma once
// Logs to the systemd journal with their priorities. Under systemd, stderr is a stream to journald
// (JOURNAL_STREAM names its device and inode); a line that starts with "<N>" (sd-daemon(3): SD_ERR is "<3>",
// SD_WARNING "<4>", SD_INFO "<6>", SD_DEBUG "<7>") is stored at priority N. So `journalctl -u fsd -p warning`
// shows exactly the warnings and worse. Elsewhere (a terminal, a test's pipe) the lines stay as they were.
namespace fsd {

// When stderr is the journal's stream: every logger's lines (those that exist and those made later) carry their
// priority and no time of their own (the journal stamps them). Returns whether it switched. Call once, after
// init_logging and before the run's threads log.
bool log_to_journal_if_there();

}  // namespace fsd
