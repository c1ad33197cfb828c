// SPDX-License-Identifier: Apache-2.0
// phasor — the scratch buffer's slow paths (scratch_buffer.h).
#include "core/scratch_buffer.h"

#include <algorithm>

namespace phasor {

ScratchBuffer::ScratchBuffer(std::size_t blockBytes)
    : block_(new std::byte[std::max<std::size_t>(blockBytes, 64)]), size_(std::max<std::size_t>(blockBytes, 64)) {}

void *ScratchBuffer::Grow(std::size_t bytes, std::size_t align) {
    fullBytes_ += size_;
    full_.push_back(std::move(block_));
    size_ = std::max(2 * size_, bytes + align);
    block_.reset(new std::byte[size_]);
    offset_ = 0;
    return Alloc(bytes, align);
}

void ScratchBuffer::Reset() {
    if (!full_.empty()) {
        // One block of the whole size the last sample needed: no growth next time.
        size_ += fullBytes_;
        full_.clear();
        fullBytes_ = 0;
        block_.reset(new std::byte[size_]);
    }
    offset_ = 0;
}

}  // namespace phasor
