// SPDX-License-Identifier: Apache-2.0
// phasor — a per-thread bump allocator for short-lived objects (pbrt-v4's ScratchBuffer): the
// kernels an integrator prepares at the vertices of one pixel sample (Material::Prepare) live
// here and are dropped together when the render loop resets the buffer before the next sample.
//
// Allocation is a pointer bump; nothing is freed one by one and no destructor runs, so only
// trivially destructible types may be placed here (New and NewArray check it at compile time).
// A buffer belongs to one thread: the render loop keeps one per worker thread and passes it
// explicitly (PixelIntegrator::EstimatePixel). When a sample needs more than the current block,
// further blocks are taken; the next Reset merges them into one block of the total size, so a
// thread settles on a single block after its largest sample.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace phasor {

class ScratchBuffer {
  public:
    /// `blockBytes`: the first block's size (grown on demand).
    explicit ScratchBuffer(std::size_t blockBytes = 16 * 1024);
    ScratchBuffer(const ScratchBuffer &) = delete;
    ScratchBuffer &operator=(const ScratchBuffer &) = delete;
    ScratchBuffer(ScratchBuffer &&) noexcept = default;
    ScratchBuffer &operator=(ScratchBuffer &&) noexcept = default;

    /// Constructs a T in the buffer; valid until the next Reset.
    template <typename T, typename... Args>
    T *New(Args &&...args) {
        static_assert(std::is_trivially_destructible_v<T>, "ScratchBuffer runs no destructors");
        return ::new (Alloc(sizeof(T), alignof(T))) T(std::forward<Args>(args)...);
    }
    /// Uninitialised room for n objects of type T (construct them with placement new); valid until
    /// the next Reset.
    template <typename T>
    T *Room(std::size_t n) {
        static_assert(std::is_trivially_destructible_v<T>, "ScratchBuffer runs no destructors");
        return static_cast<T *>(Alloc(n * sizeof(T), alignof(T)));
    }

    /// Drops every object allocated since the last Reset.
    void Reset();

    /// A position in the buffer, to drop what was allocated after it (Rewind): nested, short-lived
    /// preparations (a Newton solve's trial kernels) inside a sample's longer-lived ones.
    struct Mark {
        std::size_t blocks = 0, offset = 0;
    };
    Mark Save() const { return Mark{full_.size(), offset_}; }
    /// Drops the objects allocated since `m` (which must be from this buffer since its last Reset).
    /// If a new block was started since, the memory is reclaimed at the next Reset instead.
    void Rewind(const Mark &m) {
        if (m.blocks == full_.size()) offset_ = m.offset;
    }
    /// Bytes handed out since the last Reset (tests, statistics).
    std::size_t Used() const { return fullBytes_ + offset_; }

  private:
    void *Alloc(std::size_t bytes, std::size_t align) {
        const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(block_.get());
        const std::size_t start = ((base + offset_ + align - 1) & ~std::uintptr_t(align - 1)) - base;
        if (start + bytes <= size_) {
            offset_ = start + bytes;
            return block_.get() + start;
        }
        return Grow(bytes, align);
    }
    /// Retires the current block and starts one that holds `bytes` at `align`.
    void *Grow(std::size_t bytes, std::size_t align);

    std::unique_ptr<std::byte[]> block_;
    std::size_t size_ = 0, offset_ = 0;
    std::vector<std::unique_ptr<std::byte[]>> full_;  // blocks retired since the last Reset
    std::size_t fullBytes_ = 0;                       // their total size
};

}  // namespace phasor
