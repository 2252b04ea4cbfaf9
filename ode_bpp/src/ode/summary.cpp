// The process summary line (ode/summary.h): printed at exit, and by the handlers of SIGINT and
// SIGTERM before the signal takes its default course.
//
// Async-signal safety (docs/launcher.md): the handler reads only lock-free counters (ODE's
// dGetMLCPProcessStats and our atomics), formats without stdio or allocation, and uses write(2),
// open(2) and close(2). The environment is read once at load, never in a handler.
#include "ode/summary.h"

#include <ode/mlcp.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

namespace ode_bpp::summary {
namespace {

enum class Mode { Off, Stepped, Always };

struct Settings {
    Mode mode = Mode::Off;
    const char* file = nullptr;  ///< ODE_BPP_SUMMARY_FILE, copied at load; never freed
};

Settings read_settings() {
    Settings s;
    // secure_getenv: a setuid or setgid program must not append to a file its caller names
    const char* want = secure_getenv("ODE_BPP_SUMMARY");
    if (want == nullptr || want[0] == '\0' || std::strcmp(want, "0") == 0) return s;
    s.mode = std::strcmp(want, "always") == 0 ? Mode::Always : Mode::Stepped;
    const char* file = secure_getenv("ODE_BPP_SUMMARY_FILE");
    if (file != nullptr && file[0] != '\0') s.file = strdup(file);
    return s;
}

Settings g_settings;
std::atomic<long long> g_unrouted_quicksteps{0};
std::atomic<bool> g_printed{false};
std::atomic<bool> g_sigint_at_first_step{false};
std::atomic<bool> g_sigint_armed{false};
static_assert(std::atomic<long long>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the signal handler reads these");

/// Appends text to a fixed buffer; drops what does not fit. Async-signal-safe.
class LineWriter {
public:
    LineWriter(char* out, std::size_t size) : out_(out), size_(size) {}

    LineWriter& text(const char* s) {
        while (*s != '\0') put(*s++);
        return *this;
    }
    LineWriter& integer(long long v) {
        char digits[24];
        int n = 0;
        unsigned long long u = v < 0 ? 0ULL - static_cast<unsigned long long>(v) : static_cast<unsigned long long>(v);
        do { digits[n++] = static_cast<char>('0' + u % 10); u /= 10; } while (u != 0);
        if (v < 0) put('-');
        while (n > 0) put(digits[--n]);
        return *this;
    }
    /// v with six decimals, as printf's %.6f (v >= 0 and below 9.2e12).
    LineWriter& fixed6(double v) {
        const long long micro = std::isfinite(v) && v > 0 ? std::llround(v * 1e6) : 0;
        integer(micro / 1000000).put('.');
        char frac[7] = "000000";
        long long rest = micro % 1000000;
        for (int k = 5; k >= 0; --k, rest /= 10) frac[k] = static_cast<char>('0' + rest % 10);
        return text(frac);
    }
    LineWriter& field(const char* key, long long v) { return text(" ").text(key).text("=").integer(v); }
    std::size_t finish() {
        out_[std::min(used_, size_ - 1)] = '\0';
        return std::min(used_, size_ - 1);
    }

private:
    LineWriter& put(char c) {
        if (used_ + 1 < size_) out_[used_] = c;
        ++used_;
        return *this;
    }
    char* out_;
    std::size_t size_, used_ = 0;
};

const char* signal_name(int signal_number) {
    switch (signal_number) {
        case SIGINT: return "SIGINT";
        case SIGTERM: return "SIGTERM";
        default: return "a signal";
    }
}

void write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

/// Prints the line once per process (exit and a signal may race), if the settings ask for it.
void print_once(int signal_number) {
    if (g_settings.mode == Mode::Off) return;
    const Totals t = current_totals();
    const bool stepped = t.any_island || t.steps > 0 || t.quickstep_steps > 0;
    if (!stepped && g_settings.mode != Mode::Always) return;  // helper processes of a launched program
    if (g_printed.exchange(true)) return;
    const int saved_errno = errno;
    char line[640];
    const std::size_t n = format_line(t, signal_number, line, sizeof line);
    write_all(STDERR_FILENO, line, n);
    if (g_settings.file != nullptr) {
        const int fd = open(g_settings.file, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
        if (fd >= 0) {
            write_all(fd, line, n);
            close(fd);
        }
    }
    errno = saved_errno;
}

void print_at_exit() { print_once(0); }

/// SA_RESETHAND restores the default disposition on entry, so the raise() below ends the process
/// by the signal once the handler returns: the caller sees status 128 + n, as without us.
void on_signal(int signal_number) {
    print_once(signal_number);
    raise(signal_number);
}

/// Installs on_signal for `signal_number` where the disposition is still the default: a handler
/// of the program's own (or an inherited SIG_IGN) stays as it is.
void arm(int signal_number) {
    struct sigaction current {};
    if (sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler != SIG_DFL ||
        (current.sa_flags & SA_SIGINFO) != 0)
        return;
    struct sigaction ours {};
    ours.sa_handler = &on_signal;
    sigemptyset(&ours.sa_mask);
    ours.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(signal_number, &ours, nullptr);
}

int set_up_at_load() {
    g_settings = read_settings();
    if (g_settings.mode == Mode::Off) return 0;
    // ODE's registry first, so that its teardown is registered before our exit handler, which
    // therefore runs while the registry still exists (handlers run in reverse order)
    dMLCPStepStats probe{};
    dGetMLCPProcessStats(&probe);
    std::atexit(&print_at_exit);
    arm(SIGTERM);
    arm(SIGINT);
    return 1;
}

[[maybe_unused]] const int g_set_up = set_up_at_load();

}  // namespace

void count_unrouted_quickstep() { g_unrouted_quicksteps.fetch_add(1, std::memory_order_relaxed); }

void arm_sigint_at_first_step() {
    struct sigaction current {};
    if (sigaction(SIGINT, nullptr, &current) == 0 && current.sa_handler == &on_signal) signal(SIGINT, SIG_DFL);
    g_sigint_at_first_step.store(true);
}

void note_world_step() {
    if (!g_sigint_at_first_step.load(std::memory_order_relaxed) || g_sigint_armed.load(std::memory_order_relaxed))
        return;
    if (!g_sigint_armed.exchange(true) && g_settings.mode != Mode::Off) arm(SIGINT);
}

Totals current_totals() {
    dMLCPStepStats s{};
    s.struct_size = sizeof s;
    Totals t;
    t.any_island = dGetMLCPProcessStats(&s) != 0;
    t.steps = s.steps;
    t.islands = s.islands;
    t.rows = s.rows;
    t.pivots = s.pivots;
    t.fallbacks = s.fallbacks;
    t.failures = s.failures;
    t.solve_seconds = s.seconds;
    t.solver = t.any_island ? s.solver : nullptr;
    t.quickstep_steps = g_unrouted_quicksteps.load(std::memory_order_relaxed);
    return t;
}

std::size_t format_line(const Totals& t, int signal_number, char* out, std::size_t size) {
    const bool quick_only = !t.any_island && t.quickstep_steps > 0;
    LineWriter w(out, size);
    w.text("ode-bpp: solver=").text(t.solver != nullptr ? t.solver : quick_only ? "quickstep" : "none");
    w.field("steps", t.steps).field("islands", t.islands).field("rows", t.rows).field("pivots", t.pivots);
    w.field("fallbacks", t.fallbacks).field("failures", t.failures).text(" solve_seconds=").fixed6(t.solve_seconds);
    if (t.quickstep_steps > 0) w.field("quickstep_steps", t.quickstep_steps);
    if (quick_only)
        w.text(" (every step by dWorldQuickStep, solved by ODE's QuickStep iterations, not by ode-bpp;"
               " ODE_QUICKSTEP_SOLVER=bpp or ode-bpp-run --quickstep bpp solves them exactly)");
    else if (t.quickstep_steps > 0)
        w.text(" (quickstep_steps: dWorldQuickStep steps solved by ODE's QuickStep iterations, not by ode-bpp)");
    else if (!t.any_island)
        w.text(" (no world step with constraints)");
    if (signal_number > 0) w.text(" (ended by ").text(signal_name(signal_number)).text(")");
    w.text("\n");
    return w.finish();
}

}  // namespace ode_bpp::summary
