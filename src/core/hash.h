// SPDX-License-Identifier: Apache-2.0
// phasor — non-cryptographic 64-bit hashing: the splitmix64 finaliser (seeds, sample indices) and a
// hasher of byte streams (a checkpoint's scene identity, the geometry cache's file keys).
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace phasor {

/// 64-bit mix (splitmix64 finaliser) for hashing seeds and indices. Inline: the samplers call it
/// for every dimension of every sample.
inline uint64_t MixBits(uint64_t v) {
    v ^= v >> 30;
    v *= 0xbf58476d1ce4e5b9ULL;
    v ^= v >> 27;
    v *= 0x94d049bb133111ebULL;
    v ^= v >> 31;
    return v;
}

/// A 64-bit digest of a byte stream, eight bytes at a time through MixBits; the stream's length
/// enters the digest. Stable across runs and machines of one byte order (checkpoints rely on it).
class ContentHasher {
  public:
    void Add(const void *data, std::size_t n) {
        const unsigned char *p = static_cast<const unsigned char *>(data);
        for (; n > 0; --n) {
            word_ |= uint64_t(*p++) << (8 * fill_);
            if (++fill_ == 8) Flush();
        }
    }
    template <typename T>
    void AddValue(const T &v) {
        Add(&v, sizeof v);
    }
    void AddString(const std::string &s) {
        AddValue(uint64_t(s.size()));
        Add(s.data(), s.size());
    }
    /// Adds the content of the file at `path`; false (and nothing added) if it cannot be opened.
    /// *bytes, if given, receives how many bytes were read.
    bool AddFile(const std::string &path, std::size_t *bytes = nullptr) {
        std::ifstream in(path, std::ios::binary);
        if (bytes) *bytes = 0;
        if (!in) return false;
        char buf[1 << 16];
        while (in.read(buf, sizeof buf) || in.gcount() > 0) {
            Add(buf, std::size_t(in.gcount()));
            if (bytes) *bytes += std::size_t(in.gcount());
        }
        return !in.bad();
    }
    uint64_t Digest() {
        if (fill_ > 0) Flush();
        return MixBits(h_ ^ count_);
    }

  private:
    void Flush() {
        h_ = MixBits(h_ ^ word_) + 0x9e3779b97f4a7c15ULL;
        word_ = 0;
        fill_ = 0;
        ++count_;
    }
    uint64_t h_ = 0x70686173'6f72636bULL, word_ = 0, count_ = 0;
    int fill_ = 0;
};

}  // namespace phasor
