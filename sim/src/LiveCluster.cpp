// The launcher and the worker loop of a live run (see LiveCluster.hpp).
//
// Control messages over each worker's Unix socket pair: u8 type, u32 body length (little-endian),
// body. Launcher → worker: ports, start (u8 phase ‖ input), probe (u64 wave), finish, exit, abort.
// Worker → launcher: ready (u16 port), error (u8 kind ‖ text; kind 2 = bad input), progress (u64),
// probe reply (u64 wave, u8 idle, u64 sent, u64 received, u64 kernel drops), result (bytes), stats.
#include "laguerre/sim/LiveCluster.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/read.hpp>
#include <array>
#include <cerrno>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <random>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

namespace asio = boost::asio;

namespace {
enum : std::uint8_t {
  msg_ports = 1,
  msg_start = 2,
  msg_probe = 3,
  msg_finish = 4,
  msg_exit = 5,
  msg_abort = 6,
  msg_ready = 101,
  msg_error = 102,
  msg_progress = 103,
  msg_probe_reply = 104,
  msg_result = 105,
  msg_stats = 106,
};
constexpr std::size_t frame_header = 5;
constexpr int fail_worker_status = 70;

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}


// Writes all of `bytes` to `fd` (blocking or not: waits for room with poll). False if the peer is gone.
bool write_all(int fd, std::span<const std::byte> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (w > 0) {
      done += static_cast<std::size_t>(w);
    } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd, POLLOUT, 0};
      ::poll(&p, 1, 100);
    } else if (w < 0 && errno == EINTR) {
      continue;
    } else {
      return false;
    }
  }
  return true;
}

// Whether `in` starts with a whole frame.
bool complete_frame(const std::vector<std::byte>& in) {
  if (in.size() < frame_header) return false;
  std::size_t at = 1;
  return in.size() >= frame_header + read_bytes<std::uint32_t>(in, at);
}

bool send_frame(int fd, std::uint8_t type, std::span<const std::byte> body) {
  std::vector<std::byte> f;
  f.reserve(frame_header + body.size());
  append_bytes(f, type);
  append_bytes(f, static_cast<std::uint32_t>(body.size()));
  f.insert(f.end(), body.begin(), body.end());
  return write_all(fd, f);
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) {
    const int code = WEXITSTATUS(status);
    return code == fail_worker_status ? "exited with status 70 (failure injected)"
                                      : "exited with status " + std::to_string(code);
  }
  if (WIFSIGNALED(status)) return "was killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "ended (status " + std::to_string(status) + ")";
}

// The worker process: one io_context, one UdpHost, the control socket. Never returns.
class WorkerLoop {
public:
  WorkerLoop(int fd, std::size_t self, const core::PlanarGraph& g, std::vector<std::size_t> process_of,
             const LiveConfig& config, LiveProgram& program, UdpHost::PhaseOf phase_of)
      : fd_(fd), self_(self), config_(config), program_(program), control_(io_, ::dup(fd)),
        host_(io_, g, std::move(process_of), self, host_config(config, self), std::move(phase_of)) {}

  [[noreturn]] void run() {
    std::vector<std::byte> body;
    append_bytes(body, host_.port());
    reply(msg_ready, body);
    host_.set_after_events([this] { after_events(); });
    host_.start_receiving();
    read_header();
    io_.run();
    ::_exit(exit_status_);
  }

private:
  static UdpHostConfig host_config(const LiveConfig& config, std::size_t self) {
    UdpHostConfig h = config.host;
    h.port = config.base_port == 0 ? 0 : static_cast<std::uint16_t>(config.base_port + self);
    return h;
  }

  void reply(std::uint8_t type, std::span<const std::byte> body) {
    if (!send_frame(fd_, type, body)) ::_exit(3);  // the launcher is gone
  }

  void read_header() {
    asio::async_read(control_, asio::buffer(header_), [this](const boost::system::error_code& ec, std::size_t) {
      if (ec) ::_exit(3);  // the launcher is gone: end quietly
      std::size_t at = 1;
      const auto length = read_bytes<std::uint32_t>(std::span<const std::byte>(header_), at);
      body_.resize(length);
      asio::async_read(control_, asio::buffer(body_), [this](const boost::system::error_code& e, std::size_t) {
        if (e) ::_exit(3);
        handle(static_cast<std::uint8_t>(header_[0]), body_);
        if (!stopping_) read_header();
      });
    });
  }

  void handle(std::uint8_t type, std::span<const std::byte> body) {
    std::size_t at = 0;
    switch (type) {
      case msg_ports: {
        std::vector<std::uint16_t> ports;
        while (at < body.size()) ports.push_back(read_bytes<std::uint16_t>(body, at));
        host_.set_ports(std::move(ports));
        break;
      }
      case msg_start: {
        phase_ = read_bytes<std::uint8_t>(body, at);
        if (config_.fail_worker && *config_.fail_worker == self_) ::_exit(fail_worker_status);
        last_progress_ = ~std::uint64_t{0};
        program_.start_phase(phase_, body.subspan(1), host_);
        in_phase_ = true;
        after_events();
        break;
      }
      case msg_probe: {
        const auto wave = read_bytes<std::uint64_t>(body, at);
        std::vector<std::byte> r;
        append_bytes(r, wave);
        append_bytes(r, static_cast<std::uint8_t>(host_.idle()));
        append_bytes(r, host_.counters().datagrams_sent);
        append_bytes(r, host_.counters().datagrams_received);
        append_bytes(r, host_.kernel_drops());
        reply(msg_probe_reply, r);
        break;
      }
      case msg_finish: {
        in_phase_ = false;
        reply(msg_result, program_.finish_phase(phase_, host_));
        break;
      }
      case msg_exit: {
        host_.kernel_drops();
        std::vector<std::byte> r;
        append_bytes(r, host_.counters());
        reply(msg_stats, r);
        stopping_ = true;
        io_.stop();
        break;
      }
      default:  // abort, or anything unexpected
        exit_status_ = 4;
        stopping_ = true;
        io_.stop();
    }
  }

  void after_events() {
    if (!in_phase_) return;
    // Progress scans the nodes: at most every 2 ms while busy, always when the host is idle.
    const std::int64_t t = steady_ns();
    if (!host_.idle() && t - last_check_ < 2'000'000) return;
    last_check_ = t;
    const std::uint64_t p = program_.progress(host_);
    if (p == last_progress_) return;
    last_progress_ = p;
    std::vector<std::byte> r;
    append_bytes(r, p);
    reply(msg_progress, r);
  }

  int fd_;
  std::size_t self_;
  const LiveConfig& config_;
  LiveProgram& program_;
  asio::io_context io_;
  asio::posix::stream_descriptor control_;
  UdpHost host_;
  std::array<std::byte, frame_header> header_{};
  std::vector<std::byte> body_;
  std::uint8_t phase_ = 0;
  bool in_phase_ = false;
  bool stopping_ = false;
  int exit_status_ = 0;
  std::uint64_t last_progress_ = ~std::uint64_t{0};
  std::int64_t last_check_ = 0;
};

[[noreturn]] void worker_main(int fd, std::size_t self, const core::PlanarGraph& g, std::vector<std::size_t> process_of,
                              const LiveConfig& config, LiveProgram& program, UdpHost::PhaseOf phase_of) {
  std::uint8_t kind = 1;
  std::string what;
  try {
    WorkerLoop loop(fd, self, g, std::move(process_of), config, program, std::move(phase_of));
    loop.run();
  } catch (const core::InputError& e) {
    kind = 2;
    what = e.what();
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
    what = "unknown exception";
  }
  std::vector<std::byte> body;
  append_bytes(body, kind);
  for (const char c : what) body.push_back(static_cast<std::byte>(c));
  send_frame(fd, msg_error, body);
  ::_exit(kind);
}
}  // namespace

struct LiveCluster::Worker {
  pid_t pid = -1;
  int fd = -1;
  std::size_t nodes = 0, first = 0;  // how many vertices it hosts, the smallest
  std::uint16_t port = 0;
  std::vector<std::byte> in;
  bool reaped = false;
  int status = 0;
  rusage usage{};
  std::uint64_t progress = 0;
  bool finished = false;  // sent its stats: its end of file is expected
  bool closed = false;    // end of file seen
};

struct LiveCluster::Message {
  std::uint8_t type = 0;  // 0: none (the wait expired)
  std::vector<std::byte> body;
};

std::vector<std::size_t> LiveCluster::partition_blocks(std::size_t n, std::size_t processes) {
  std::vector<std::size_t> end(processes);
  std::size_t at = 0;
  for (std::size_t k = 0; k < processes; ++k) {
    at += n / processes + (k < n % processes ? 1 : 0);
    end[k] = at;
  }
  return end;
}

LiveCluster::LiveCluster(const core::PlanarGraph& g, LiveConfig config, LiveProgram& program, UdpHost::PhaseOf phase_of)
    : config_(config) {
  const std::size_t n = g.num_vertices();
  if (config_.processes < 1 || config_.processes > n)
    throw core::InputError("--processes", 0,
                           "between 1 and the number of nodes (" + std::to_string(n) + "), found " +
                               std::to_string(config_.processes));
  if (config_.base_port != 0 && config_.base_port + config_.processes - 1 > 65535)
    throw core::InputError("--base-port", 0,
                           "ports base_port .. base_port + processes - 1 within 1..65535, found base port " +
                               std::to_string(config_.base_port) + " for " + std::to_string(config_.processes) +
                               " processes");
  if (!(config_.timeout_seconds > 0))
    throw core::InputError("--timeout", 0, "a positive number of seconds, found " + std::to_string(config_.timeout_seconds));
  const std::int64_t start = steady_ns();
  deadline_ = start + static_cast<std::int64_t>(config_.timeout_seconds * 1e9);
  config_.host.epoch = start;
  config_.host.run_tag = static_cast<std::uint32_t>(std::random_device{}());
  std::vector<std::size_t> process_of = config_.process_of;
  if (process_of.empty()) {
    const std::vector<std::size_t> ends = partition_blocks(n, config_.processes);
    process_of.resize(n);
    for (std::size_t k = 0, v = 0; k < ends.size(); ++k)
      for (; v < ends[k]; ++v) process_of[v] = k;
  }
  if (process_of.size() != n)
    throw core::InputError("--partition", 0,
                           "one worker per vertex (" + std::to_string(n) + "), found " + std::to_string(process_of.size()));
  workers_.resize(config_.processes);
  for (std::size_t v = n; v-- > 0;) {
    if (process_of[v] >= config_.processes)
      throw core::InputError("--partition", 0,
                             "workers 0.." + std::to_string(config_.processes - 1) + ", found worker " +
                                 std::to_string(process_of[v]) + " for vertex " + std::to_string(v));
    Worker& w = workers_[process_of[v]];
    ++w.nodes;
    w.first = v;
  }
  for (std::size_t k = 0; k < workers_.size(); ++k)
    if (workers_[k].nodes == 0)
      throw core::InputError("--partition", 0, "every worker hosting a vertex, found none for worker " + std::to_string(k));
  std::fflush(nullptr);  // nothing buffered is written twice by the children
  for (std::size_t k = 0; k < config_.processes; ++k) {
    Worker& w = workers_[k];
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0)
      fail("cannot create the control channel of worker " + std::to_string(k) + ": " + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
      const int e = errno;
      ::close(sv[0]);
      ::close(sv[1]);
      fail("worker process " + std::to_string(k) + " cannot start (fork: " + std::strerror(e) + ")");
    }
    if (pid == 0) {
      ::close(sv[0]);
      for (std::size_t j = 0; j < k; ++j) ::close(workers_[j].fd);
      worker_main(sv[1], k, g, process_of, config_, program, phase_of);
    }
    ::close(sv[1]);
    w.pid = pid;
    w.fd = sv[0];
    ::fcntl(w.fd, F_SETFL, ::fcntl(w.fd, F_GETFL) | O_NONBLOCK);
  }
  std::size_t ready = 0;
  while (ready < workers_.size()) {
    std::size_t k = 0;
    const Message m = wait_message(k, -1);
    if (m.type != msg_ready) fail("worker " + std::to_string(k) + " sent an unexpected message while starting");
    std::size_t at = 0;
    workers_[k].port = read_bytes<std::uint16_t>(m.body, at);
    ++ready;
  }
  std::vector<std::byte> ports;
  for (const Worker& w : workers_) append_bytes(ports, w.port);
  broadcast(msg_ports, ports);
}

LiveCluster::~LiveCluster() {
  for (Worker& w : workers_) {
    if (!w.reaped && w.pid > 0) {
      ::kill(w.pid, SIGKILL);
      ::wait4(w.pid, &w.status, 0, &w.usage);
      w.reaped = true;
    }
    if (w.fd >= 0) ::close(w.fd);
  }
}

void LiveCluster::send(std::size_t k, std::uint8_t type, std::span<const std::byte> body) {
  if (!send_frame(workers_[k].fd, type, body)) {
    std::size_t from = k;
    wait_message(from, 100);  // reports the worker's death if that is why
    fail("worker " + std::to_string(k) + " does not take control messages any more");
  }
}

void LiveCluster::broadcast(std::uint8_t type, std::span<const std::byte> body) {
  for (std::size_t k = 0; k < workers_.size(); ++k) send(k, type, body);
}

void LiveCluster::stop_all() {
  for (Worker& w : workers_)
    if (!w.reaped && w.pid > 0) send_frame(w.fd, msg_abort, {});
  const std::int64_t grace = steady_ns() + 1'000'000'000;
  for (Worker& w : workers_) {
    while (!w.reaped && w.pid > 0) {
      const pid_t r = ::wait4(w.pid, &w.status, WNOHANG, &w.usage);
      if (r == w.pid || r < 0) {
        w.reaped = true;
        break;
      }
      if (steady_ns() > grace) ::kill(w.pid, SIGKILL);
      ::usleep(2000);
    }
  }
}

void LiveCluster::fail(const std::string& what, bool input_error) {
  stop_all();
  if (input_error) throw core::InputError(what);
  throw std::runtime_error(what);
}

LiveCluster::Message LiveCluster::wait_message(std::size_t& from, int max_wait_ms) {
  const std::int64_t until = max_wait_ms < 0 ? deadline_ : std::min<std::int64_t>(deadline_, steady_ns() + std::int64_t{max_wait_ms} * 1'000'000);
  for (;;) {
    // A complete frame already buffered?
    for (std::size_t k = 0; k < workers_.size(); ++k) {
      std::vector<std::byte>& in = workers_[k].in;
      if (!complete_frame(in)) continue;
      std::size_t at = 1;
      const auto length = read_bytes<std::uint32_t>(in, at);
      Message m{static_cast<std::uint8_t>(in[0]), std::vector<std::byte>(in.begin() + frame_header,
                                                                          in.begin() + static_cast<std::ptrdiff_t>(frame_header + length))};
      in.erase(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(frame_header + length));
      from = k;
      if (m.type == msg_error) {
        const bool input = !m.body.empty() && m.body[0] == std::byte{2};
        const std::string text(reinterpret_cast<const char*>(m.body.data()) + 1, m.body.size() - (m.body.empty() ? 0 : 1));
        fail("worker " + std::to_string(k) + " (" + std::to_string(workers_[k].nodes) + " nodes from vertex " +
                 std::to_string(workers_[k].first) + "): " + text,
             input);
      }
      return m;
    }
    const std::int64_t now = steady_ns();
    if (now >= deadline_)
      fail("the live run timed out after " + std::to_string(config_.timeout_seconds) + " s (phase " +
           std::to_string(phase_) + "); every worker was stopped");
    if (now >= until) return {};
    std::vector<pollfd> fds;
    for (const Worker& w : workers_) fds.push_back({w.closed ? -1 : w.fd, POLLIN, 0});
    const int wait_ms = static_cast<int>(std::max<std::int64_t>(1, (until - now) / 1'000'000));
    if (::poll(fds.data(), fds.size(), wait_ms) < 0 && errno != EINTR)
      fail(std::string("poll failed: ") + std::strerror(errno));
    for (std::size_t k = 0; k < workers_.size(); ++k) {
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      std::byte buf[65536];
      for (;;) {
        const ssize_t r = ::read(workers_[k].fd, buf, sizeof buf);
        if (r > 0) {
          workers_[k].in.insert(workers_[k].in.end(), buf, buf + r);
          continue;
        }
        if (r < 0 && (errno == EAGAIN || errno == EINTR)) break;
        // End of file: the worker is gone. Report it unless it left a message to read first.
        if (complete_frame(workers_[k].in)) break;
        Worker& w = workers_[k];
        if (w.finished) {
          w.closed = true;
          break;
        }
        ::wait4(w.pid, &w.status, 0, &w.usage);
        w.reaped = true;
        fail("worker " + std::to_string(k) + " (" + std::to_string(w.nodes) + " nodes from vertex " + std::to_string(w.first) +
             ", port " + std::to_string(w.port) + ") " + describe_status(w.status) +
             " during phase " + std::to_string(phase_) + "; the other workers were stopped");
      }
    }
  }
}

std::vector<std::vector<std::byte>> LiveCluster::run_phase(std::span<const std::byte> input, std::uint64_t goal) {
  const std::int64_t start = steady_ns();
  std::vector<std::byte> body;
  append_bytes(body, phase_);
  body.insert(body.end(), input.begin(), input.end());
  for (Worker& w : workers_) w.progress = 0;
  broadcast(msg_start, body);
  std::uint64_t wave = 0;
  bool probing = false, goal_reached = false;
  std::size_t replies = 0;
  bool all_idle = true;
  std::uint64_t sent = 0, received = 0, drops = 0;
  std::vector<std::uint64_t> counts, previous;  // per worker: sent, received of the last two waves
  // Before the goal, a wave every 100 ms still looks for kernel drops (fatal without reliability).
  constexpr std::int64_t check_every = 100'000'000;
  std::int64_t next_check = start + check_every;
  for (;;) {
    std::uint64_t total = 0;
    for (const Worker& w : workers_) total += w.progress;
    if (!probing && (total >= goal || steady_ns() >= next_check)) {
      probing = true;
      goal_reached = total >= goal;
      ++wave;
      replies = 0;
      all_idle = true;
      sent = received = drops = 0;
      counts.assign(2 * workers_.size(), 0);
      std::vector<std::byte> b;
      append_bytes(b, wave);
      broadcast(msg_probe, b);
    }
    std::size_t k = 0;
    const int wait_ms = probing ? -1 : static_cast<int>(std::max<std::int64_t>(1, (next_check - steady_ns()) / 1'000'000));
    const Message m = wait_message(k, wait_ms);
    std::size_t at = 0;
    if (m.type == msg_progress) {
      workers_[k].progress = read_bytes<std::uint64_t>(m.body, at);
    } else if (m.type == msg_probe_reply) {
      if (read_bytes<std::uint64_t>(m.body, at) != wave) continue;
      all_idle = all_idle && read_bytes<std::uint8_t>(m.body, at) != 0;
      counts[2 * k] = read_bytes<std::uint64_t>(m.body, at);
      counts[2 * k + 1] = read_bytes<std::uint64_t>(m.body, at);
      sent += counts[2 * k];
      received += counts[2 * k + 1];
      drops += read_bytes<std::uint64_t>(m.body, at);
      if (++replies < workers_.size()) continue;
      probing = false;
      if (drops > 0 && config_.lossless)
        fail("the kernel dropped " + std::to_string(drops) +
             " datagram(s) (a receive buffer was full) and the nodes run without the reliability layer, so "
             "the run cannot finish: rerun with a larger socket buffer or the reliability layer on "
             "(laguerre live --socket-buffer, --reliable)");
      if (!goal_reached) {
        next_check = steady_ns() + check_every;
        previous.clear();
        continue;
      }
      const bool quiet = all_idle && sent == received + drops;
      if (quiet && counts == previous) break;
      previous = quiet ? counts : std::vector<std::uint64_t>{};
      if (!quiet) std::this_thread::sleep_for(std::chrono::milliseconds(1));  // let the workers run a little
    }
  }
  broadcast(msg_finish, {});
  std::vector<std::vector<std::byte>> results(workers_.size());
  std::vector<bool> got(workers_.size(), false);
  for (std::size_t done = 0; done < workers_.size();) {
    std::size_t k = 0;
    Message m = wait_message(k, -1);
    if (m.type != msg_result || got[k]) continue;
    got[k] = true;
    results[k] = std::move(m.body);
    ++done;
  }
  phase_seconds_.push_back(static_cast<double>(steady_ns() - start) * 1e-9);
  ++phase_;
  return results;
}

std::vector<WorkerReport> LiveCluster::finish() {
  broadcast(msg_exit, {});
  std::vector<WorkerReport> reports(workers_.size());
  for (std::size_t done = 0; done < workers_.size();) {
    std::size_t k = 0;
    const Message m = wait_message(k, -1);
    if (m.type != msg_stats) continue;
    std::size_t at = 0;
    reports[k].counters = read_bytes<UdpCounters>(m.body, at);
    workers_[k].finished = true;
    ++done;
  }
  for (std::size_t k = 0; k < workers_.size(); ++k) {
    Worker& w = workers_[k];
    ::wait4(w.pid, &w.status, 0, &w.usage);
    w.reaped = true;
    reports[k].nodes = w.nodes;
    reports[k].first = w.first;
    reports[k].port = w.port;
    reports[k].peak_memory_bytes = static_cast<std::uint64_t>(w.usage.ru_maxrss) * 1024;
    reports[k].cpu_seconds = static_cast<double>(w.usage.ru_utime.tv_sec + w.usage.ru_stime.tv_sec) +
                             1e-6 * static_cast<double>(w.usage.ru_utime.tv_usec + w.usage.ru_stime.tv_usec);
  }
  return reports;
}

}  // namespace laguerre::sim
