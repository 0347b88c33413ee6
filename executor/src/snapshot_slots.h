#pragma once
/// \file
/// \brief Publication of immutable snapshots from one writer thread to any number of
///        real-time readers: readers never lock, never allocate and never free.
///
/// Three slots hold owned snapshots; `current_` names the published one (-1: none). A
/// reader announces itself on the slot it saw published (readers_[i] += 1) and then checks
/// that the slot is still the published one; if a publication slipped in between, it
/// withdraws and tries again (lock-free: a retry needs a publication inside a window of a
/// few instructions). A writer fills a slot that is neither published nor announced by any
/// reader, then publishes it; it waits (yielding) only while a reader still holds every
/// other slot, which lasts one sample. Old snapshots are destroyed by the writer, so the
/// reader side never frees memory. All slot atomics are sequentially consistent: the
/// argument that a writer never reuses a slot a reader has confirmed relies on a single
/// total order of the announce, the confirm load and the writer's check.

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

namespace rbsf::executor::detail {

/// \brief Slots of immutable T published by writers (serialised) to lock-free readers.
template <class T>
class SnapshotSlots {
 public:
  static constexpr int kSlots = 3;

  /// \brief A reader's hold on the published snapshot; empty when none is published.
  class Reader {
   public:
    explicit Reader(const SnapshotSlots& slots) noexcept : slots_(slots) {
      for (;;) {
        const int i = slots_.current_.load();
        if (i < 0) return;
        slots_.readers_[i].fetch_add(1);
        if (slots_.current_.load() == i) {
          slot_ = i;
          item_ = slots_.items_[i].get();
          return;
        }
        slots_.readers_[i].fetch_sub(1);
      }
    }
    ~Reader() {
      if (slot_ >= 0) slots_.readers_[slot_].fetch_sub(1);
    }
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    /// \brief The snapshot, valid while this Reader lives; nullptr when none.
    const T* get() const noexcept { return item_; }

   private:
    const SnapshotSlots& slots_;
    int slot_ = -1;
    const T* item_ = nullptr;
  };

  /// \brief Make `item` the published snapshot (nullptr: publish nothing). Destroys the
  ///        snapshot previously held by the slot it reuses. Writers are serialised.
  void publish(std::unique_ptr<const T> item) {
    const std::lock_guard<std::mutex> lock(writer_mutex_);
    if (!item) {
      current_.store(-1);
      return;
    }
    const int cur = current_.load();
    for (;;) {
      for (int j = 0; j < kSlots; ++j) {
        if (j == cur || readers_[j].load() != 0) continue;
        items_[j] = std::move(item);
        current_.store(j);
        return;
      }
      std::this_thread::yield();
    }
  }

  /// \brief True when a snapshot is published.
  bool published() const noexcept { return current_.load() >= 0; }

 private:
  std::array<std::unique_ptr<const T>, kSlots> items_;
  mutable std::array<std::atomic<int>, kSlots> readers_{};
  std::atomic<int> current_{-1};
  std::mutex writer_mutex_;  // writers only; never taken by a reader
};

}  // namespace rbsf::executor::detail
