// SPDX-License-Identifier: Apache-2.0
// The per-thread bump allocator of prepared kernels (core/scratch_buffer.h): alignment, growth past
// a block, Reset merging the blocks of a large sample into one, Rewind to a mark.
#include "core/scratch_buffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace phasor {
namespace {

struct alignas(32) Wide {
    double v[4] = {1, 2, 3, 4};
};

TEST(ScratchBuffer, ObjectsAreAlignedAndConstructed) {
    ScratchBuffer s(256);
    auto *c = s.New<char>('x');
    auto *w = s.New<Wide>();
    auto *d = s.New<double>(2.5);
    EXPECT_EQ(*c, 'x');
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(w) % alignof(Wide), 0u);
    EXPECT_EQ(w->v[3], 4);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(d) % alignof(double), 0u);
    EXPECT_EQ(*d, 2.5);
    int *room = s.Room<int>(10);
    for (int i = 0; i < 10; ++i) room[i] = i;
    EXPECT_EQ(room[9], 9);
    EXPECT_EQ(*d, 2.5) << "Room overlapped an earlier object";
}

TEST(ScratchBuffer, GrowsPastABlockAndSettlesOnOneAfterReset) {
    ScratchBuffer s(128);
    std::vector<double *> kept;
    for (int i = 0; i < 100; ++i) kept.push_back(s.New<double>(i));  // 800 bytes: several blocks
    for (int i = 0; i < 100; ++i) EXPECT_EQ(*kept[std::size_t(i)], i) << "an object moved or was overwritten";
    const std::size_t used = s.Used();
    EXPECT_GE(used, 800u);
    s.Reset();
    EXPECT_EQ(s.Used(), 0u);
    // The next sample of the same size fits in the merged block: consecutive addresses.
    double *first = s.New<double>(0.0);
    for (int i = 1; i < 100; ++i) EXPECT_EQ(s.New<double>(i), first + i);
}

TEST(ScratchBuffer, RewindDropsWhatCameAfterTheMark) {
    ScratchBuffer s(1024);
    double *a = s.New<double>(1.0);
    const ScratchBuffer::Mark m = s.Save();
    double *b = s.New<double>(2.0);
    s.Rewind(m);
    double *c = s.New<double>(3.0);
    EXPECT_EQ(b, c) << "the rewound room is handed out again";
    EXPECT_EQ(*a, 1.0);
    // A mark from before a new block: Rewind keeps everything (reclaimed at the next Reset).
    const ScratchBuffer::Mark m2 = s.Save();
    double *big = s.Room<double>(1000);  // a new block
    big[999] = 7;
    s.Rewind(m2);
    double *after = s.New<double>(8.0);
    EXPECT_EQ(after, big + 1000) << "rewound across a block";
    EXPECT_EQ(big[999], 7);
}

}  // namespace
}  // namespace phasor
