// A small stand-in for libFuzzer's driver, for builds without clang's -fsanitize=fuzzer (the default
// gcc build and its sanitizer preset). It replays every input file given (the seed corpus and the
// regressions), then, for a time budget, runs deterministic mutations of them: no coverage feedback,
// but the same harnesses, and under ASan/UBSan the same sanitizer checks as libFuzzer.
//
//   <harness> [--seconds S] [--runs N] [--seed K] [--max-len L] [--timeout T] [--out DIR] PATH...
//
// PATH is a file or a folder (its regular files, recursively, in name order). Mutated input i (from 0)
// is a function of K, i and the inputs only, so `--seed K --runs i+1` replays a failure. A failure (a
// finding's abort, a crash, a sanitizer report, an escaped exception, an input running longer than T
// seconds) writes the input to DIR/<harness>-crash-<K>-<i> (or -replay-<file> for a replayed file),
// names it on stderr and exits non-zero.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define LAGUERRE_FUZZ_HAVE_SANITIZER 1
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;
using Bytes = std::string;  // bytes, not necessarily text

// The input being run and where it goes if it fails (read by the signal handlers).
const Bytes* current_input = nullptr;
char failure_path[4096] = {0};
bool in_signal_handler = false;

void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n <= 0) return;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void say(const char* text) { write_all(2, text, std::strlen(text)); }

// Async-signal-safe: saves the current input and says where.
void save_current_input() {
  if (current_input == nullptr || failure_path[0] == '\0') return;
  const int fd = ::open(failure_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    say("fuzz: cannot write the failing input to ");
  } else {
    write_all(fd, current_input->data(), current_input->size());
    ::close(fd);
    say("fuzz: failing input saved to ");
  }
  say(failure_path);
  say("\n");
  current_input = nullptr;
}

extern "C" void on_fatal_signal(int signal) {
  if (!in_signal_handler) {
    in_signal_handler = true;
    if (signal == SIGALRM) say("fuzz: timeout (the input ran longer than --timeout seconds)\n");
    save_current_input();
  }
  std::signal(signal == SIGALRM ? SIGABRT : signal, SIG_DFL);
  std::raise(signal == SIGALRM ? SIGABRT : signal);
}

#ifdef LAGUERRE_FUZZ_HAVE_SANITIZER
extern "C" void on_sanitizer_death() { save_current_input(); }
#endif

void install_handlers() {
  static std::vector<char> alternate_stack(1 << 16);  // so that a stack overflow still reaches the handler
  stack_t ss{};
  ss.ss_sp = alternate_stack.data();
  ss.ss_size = alternate_stack.size();
  ::sigaltstack(&ss, nullptr);
  struct sigaction sa{};
  sa.sa_handler = on_fatal_signal;
  sa.sa_flags = SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGALRM}) ::sigaction(s, &sa, nullptr);
#ifdef LAGUERRE_FUZZ_HAVE_SANITIZER
  __sanitizer_set_death_callback(on_sanitizer_death);
#endif
}

struct Options {
  double seconds = 0;
  std::uint64_t runs = UINT64_MAX;
  std::uint64_t seed = 1;
  std::size_t max_len = 4096;
  unsigned timeout = 10;
  fs::path out = ".";
  std::vector<fs::path> paths;
};

[[noreturn]] void usage(const char* program, const std::string& problem) {
  std::fprintf(stderr,
               "%s: %s\nusage: %s [--seconds S] [--runs N] [--seed K] [--max-len L] [--timeout T] [--out DIR] "
               "PATH...\n",
               program, problem.c_str(), program);
  std::exit(2);
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) != 0) {
      o.paths.emplace_back(a);
      continue;
    }
    if (i + 1 >= argc) usage(argv[0], "missing value after " + a);
    const std::string v = argv[++i];
    try {
      if (a == "--seconds") o.seconds = std::stod(v);
      else if (a == "--runs") o.runs = std::stoull(v);
      else if (a == "--seed") o.seed = std::stoull(v);
      else if (a == "--max-len") o.max_len = std::stoul(v);
      else if (a == "--timeout") o.timeout = static_cast<unsigned>(std::stoul(v));
      else if (a == "--out") o.out = v;
      else usage(argv[0], "unknown option " + a);
    } catch (const std::logic_error&) {
      usage(argv[0], "bad value '" + v + "' for " + a);
    }
  }
  return o;
}

std::vector<fs::path> input_files(const Options& o, const char* program) {
  std::vector<fs::path> files;
  for (const fs::path& p : o.paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> in_dir;
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) in_dir.push_back(e.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else if (fs::is_regular_file(p, ec)) {
      files.push_back(p);
    } else {
      usage(program, "no such file or folder: " + p.string());
    }
  }
  return files;
}

Bytes read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs the harness on `input`; on failure the input goes to `path`.
void run(const Bytes& input, const fs::path& path, unsigned timeout) {
  std::snprintf(failure_path, sizeof failure_path, "%s", path.c_str());
  current_input = &input;
  ::alarm(timeout);
  try {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: an exception escaped the harness: %s\n", e.what());
    std::abort();
  }
  ::alarm(0);
  current_input = nullptr;
}

// Deterministic mutations of the seeds (the mutations libFuzzer starts with, plus text-aware ones:
// lines, tokens of the seeds, boundary numbers).
class Mutator {
public:
  Mutator(std::vector<Bytes> seeds, std::uint64_t seed, std::size_t max_len)
      : seeds_(std::move(seeds)), rng_(seed), max_len_(max_len) {
    if (seeds_.empty()) seeds_.emplace_back();
    for (const Bytes& s : seeds_) collect_tokens(s);
    for (const char* t : {"0", "-1", "1", "65535", "65536", "4294967296", "18446744073709551616", "1e308", "1e-300",
                          "-0", "nan", "inf", "0x10", "1e160", "\n", "#", " ", "\t", "\"", "{", "}", "[", "]", "<",
                          ">", "/", ":", ";", ",", "="})
      tokens_.emplace_back(t);
  }

  Bytes next() {
    Bytes b = pick(seeds_);
    const int count = 1 + static_cast<int>(below(4));
    for (int k = 0; k < count; ++k) mutate(b);
    if (b.size() > max_len_) b.resize(max_len_);
    return b;
  }

private:
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[below(v.size())];
  }

  void collect_tokens(const Bytes& s) {
    const auto word = [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '.' || c == '-'; };
    for (std::size_t i = 0; i < s.size() && tokens_.size() < 2000;) {
      if (!word(static_cast<unsigned char>(s[i]))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < s.size() && word(static_cast<unsigned char>(s[j]))) ++j;
      if (j - i <= 32) tokens_.push_back(s.substr(i, j - i));
      i = j;
    }
  }

  // Bounds [begin, end) of a random line of b.
  std::pair<std::size_t, std::size_t> line(const Bytes& b) {
    const std::size_t at = below(b.size());
    std::size_t begin = b.rfind('\n', at);
    begin = begin == Bytes::npos ? 0 : begin + 1;
    std::size_t end = b.find('\n', at);
    end = end == Bytes::npos ? b.size() : end + 1;
    return {begin, std::max(begin, end)};
  }

  void mutate(Bytes& b) {
    const std::size_t n = b.size();
    switch (below(11)) {
      case 0:  // flip a bit
        if (n) {
          const std::size_t at = below(n);
          b[at] = static_cast<char>(b[at] ^ (1 << below(8)));
        }
        break;
      case 1:  // replace a byte
        if (n) b[below(n)] = static_cast<char>(below(256));
        break;
      case 2:  // insert bytes
        b.insert(below(n + 1), 1 + below(4), static_cast<char>(below(256)));
        break;
      case 3: {  // delete a range
        if (!n) break;
        const std::size_t at = below(n);
        b.erase(at, 1 + below(std::min<std::size_t>(n - at, 16)));
        break;
      }
      case 4: {  // duplicate a range in place
        if (!n) break;
        const std::size_t at = below(n), len = 1 + below(std::min<std::size_t>(n - at, 64));
        b.insert(below(n + 1), b.substr(at, len));
        break;
      }
      case 5: {  // splice: a prefix of this input, a suffix of another seed
        const Bytes& other = pick(seeds_);
        b = b.substr(0, below(n + 1)) + other.substr(below(other.size() + 1));
        break;
      }
      case 6: {  // duplicate a line
        if (!n) break;
        const auto [begin, end] = line(b);
        b.insert(below(2) ? begin : end, b.substr(begin, end - begin));
        break;
      }
      case 7: {  // delete a line
        if (!n) break;
        const auto [begin, end] = line(b);
        b.erase(begin, end - begin);
        break;
      }
      case 8: {  // swap two lines
        if (!n) break;
        auto [b1, e1] = line(b);
        auto [b2, e2] = line(b);
        if (b1 > b2) std::swap(b1, b2), std::swap(e1, e2);
        if (e1 > b2) break;
        const Bytes first = b.substr(b1, e1 - b1), second = b.substr(b2, e2 - b2);
        b.replace(b2, e2 - b2, first);
        b.replace(b1, e1 - b1, second);
        break;
      }
      case 9:  // insert a token
        b.insert(below(n + 1), pick(tokens_));
        break;
      default: {  // replace a number by another
        if (!n) break;
        std::size_t at = below(n);
        while (at < n && !std::isdigit(static_cast<unsigned char>(b[at]))) ++at;
        if (at == n) break;
        std::size_t end = at;
        while (end < n && (std::isdigit(static_cast<unsigned char>(b[end])) || b[end] == '.')) ++end;
        b.replace(at, end - at, below(2) ? pick(tokens_) : std::to_string(below(1000)));
        break;
      }
    }
  }

  std::vector<Bytes> seeds_;
  std::vector<Bytes> tokens_;
  std::mt19937_64 rng_;
  std::size_t max_len_;
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  const std::string name = fs::path(argv[0]).filename().string();
  install_handlers();
  std::error_code ec;
  fs::create_directories(o.out, ec);

  std::vector<Bytes> seeds;
  for (const fs::path& f : input_files(o, argv[0])) {
    seeds.push_back(read_bytes(f));
    run(seeds.back(), o.out / (name + "-replay-" + f.filename().string()), o.timeout);
  }
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::uint64_t runs = 0, slowest_run = 0;
  double slowest = 0;
  if (o.seconds > 0) {
    Mutator mutator(seeds, o.seed, o.max_len);
    for (; runs < o.runs && elapsed() < o.seconds; ++runs) {
      const Bytes input = mutator.next();
      const double before = elapsed();
      run(input, o.out / (name + "-crash-" + std::to_string(o.seed) + "-" + std::to_string(runs)), o.timeout);
      if (const double took = elapsed() - before; took > slowest) {
        slowest = took;
        slowest_run = runs;
      }
    }
  }
  const double t = elapsed();
  std::printf("%s: %zu inputs replayed, %llu mutated executions in %.1f s (%.0f/s, slowest %.3f s: run %llu), "
              "seed %llu, no failure\n",
              name.c_str(), seeds.size(), static_cast<unsigned long long>(runs), t,
              t > 0 ? static_cast<double>(runs) / t : 0.0, slowest, static_cast<unsigned long long>(slowest_run),
              static_cast<unsigned long long>(o.seed));
  return 0;
}
