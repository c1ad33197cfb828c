// SPDX-License-Identifier: Apache-2.0
// phasor — plain values to bytes and back, for messages between MPI ranks (app/distributed.h). The
// ranks of a job run one build on one architecture, so values travel in the host's byte order; a
// short message is an error, never a read past its end.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "core/diagnostics.h"

namespace phasor {

struct ByteWriter {
    std::string bytes;
    template <typename T>
    void Put(const T &v) {
        static_assert(std::is_trivially_copyable_v<T>);
        PutBytes(&v, sizeof v);
    }
    void PutBytes(const void *p, std::size_t n) { bytes.append(static_cast<const char *>(p), n); }
    void PutString(const std::string &s) {
        Put(uint64_t(s.size()));
        bytes += s;
    }
    template <typename T>
    void PutVector(const std::vector<T> &v) {
        Put(uint64_t(v.size()));
        PutBytes(v.data(), v.size() * sizeof(T));
    }
    void PutStrings(const std::vector<std::string> &v) {
        Put(uint64_t(v.size()));
        for (const std::string &s : v) PutString(s);
    }
    void PutMap(const std::map<std::string, std::string> &m) {
        Put(uint64_t(m.size()));
        for (const auto &[k, v] : m) {
            PutString(k);
            PutString(v);
        }
    }
};

struct ByteReader {
    const char *p, *end;
    explicit ByteReader(const std::string &b) : p(b.data()), end(b.data() + b.size()) {}
    ByteReader(const char *data, std::size_t n) : p(data), end(data + n) {}
    std::size_t Left() const { return std::size_t(end - p); }
    template <typename T>
    T Get() {
        static_assert(std::is_trivially_copyable_v<T>);
        T v;
        GetBytes(&v, sizeof v);
        return v;
    }
    void GetBytes(void *out, std::size_t n) {
        if (Left() < n) throw Error("internal error: a short message between MPI ranks");
        std::memcpy(out, p, n);
        p += n;
    }
    std::string GetString() {
        std::string s(std::size_t(Get<uint64_t>()), '\0');
        GetBytes(s.data(), s.size());
        return s;
    }
    template <typename T>
    std::vector<T> GetVector() {
        const auto n = std::size_t(Get<uint64_t>());
        if (n > Left() / std::max<std::size_t>(1, sizeof(T))) throw Error("internal error: a short message between MPI ranks");
        std::vector<T> v(n);
        GetBytes(v.data(), n * sizeof(T));
        return v;
    }
    std::vector<std::string> GetStrings() {
        std::vector<std::string> v(std::size_t(Get<uint64_t>()));
        for (std::string &s : v) s = GetString();
        return v;
    }
    std::map<std::string, std::string> GetMap() {
        std::map<std::string, std::string> m;
        for (auto n = Get<uint64_t>(); n > 0; --n) {
            std::string k = GetString();
            m[k] = GetString();
        }
        return m;
    }
};

}  // namespace phasor
