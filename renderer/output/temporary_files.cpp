#include "renderer/output/temporary_files.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace kinray {
namespace {

constexpr size_t kSlots = 64;
constexpr size_t kPathBytes = 4096;

// A slot's path is written before `used` is published, and read by the handler only when `used`
// is set: the handler never allocates or locks.
struct Slot {
  std::atomic<bool> used{false};
  std::array<char, kPathBytes> path{};
};
std::array<Slot, kSlots> g_slots;
std::mutex g_claim;  // serialises claiming a slot (never taken by the handler)

extern "C" void remove_temporaries_and_die(int signal) {
  for (Slot& slot : g_slots)
    if (slot.used.load(std::memory_order_acquire)) ::unlink(slot.path.data());
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

void remove_temporaries_on_interrupt() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_die;
      sigemptyset(&action.sa_mask);
      ::sigaction(signal, &action, nullptr);
    }
  });
}

TemporaryFile::TemporaryFile(const std::string& path) : m_path(path) {
  if (path.size() + 1 > kPathBytes) return;
  const std::lock_guard lock(g_claim);
  for (size_t i = 0; i < kSlots; ++i) {
    Slot& slot = g_slots[i];
    if (slot.used.load(std::memory_order_relaxed)) continue;
    std::memcpy(slot.path.data(), path.c_str(), path.size() + 1);
    slot.used.store(true, std::memory_order_release);
    m_slot = int(i);
    return;
  }
}

TemporaryFile::~TemporaryFile() {
  if (m_slot >= 0) g_slots[size_t(m_slot)].used.store(false, std::memory_order_release);
}

}  // namespace kinray
