// SPDX-License-Identifier: Apache-2.0
// phasor — the process-wide cache of built geometry (docs/architecture.md, "What a render costs,
// and where"): triangulated meshes (a loaded OBJ, a subdivision surface) and the accelerator's
// Embree BVHs are built once per process and shared by every Scene whose geometry is the same,
// e.g. the renders of a sweep over a Define that changes only a material.
//
// An entry is found by a key that states everything its geometry depends on — the shape type,
// each geometric parameter's resolved value written exactly, a file's path, size and content
// hash — never by the name of a Define. Scenes hold entries by shared_ptr; the cache holds a
// weak_ptr to every entry and strong references to the most recently used ones up to a byte
// budget, so a sweep that builds one scene after another still finds the previous one's geometry,
// and memory is freed once no scene and no recent use keeps an entry.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

#include "core/geometry/shape.h"

namespace phasor {

/// Builds a geometry key: the kind, then `name=value` fields, each value written exactly (numbers
/// as hexadecimal floats, so two keys are equal only if every value is bit-identical).
class GeometryKey {
  public:
    explicit GeometryKey(std::string_view kind) : key_(kind) {}
    GeometryKey &Text(std::string_view name, std::string_view value);
    GeometryKey &Integer(std::string_view name, long long value);
    GeometryKey &Number(std::string_view name, double value);
    GeometryKey &Numbers(std::string_view name, const std::vector<double> &values);
    /// Both the forward and the inverse matrix (a mesh's normals use the inverse).
    GeometryKey &Matrix(std::string_view name, const Transform &t);
    /// The file's absolute path, size [bytes] and a 64-bit hash of its content, so that a file
    /// rewritten on disk gives another key. Throws phasor::Error if it cannot be read.
    GeometryKey &File(std::string_view name, const std::string &path);
    const std::string &Str() const { return key_; }

  private:
    std::string key_;
};

/// How often the geometry cache built and reused meshes and BVHs since the process started (or
/// since the last ClearGeometryCache), for tests and for `--verbose`-style reports.
struct GeometryCacheStats {
    long long meshBuilds = 0, meshReuses = 0;
    long long bvhBuilds = 0, bvhReuses = 0;
};

GeometryCacheStats GetGeometryCacheStats();
/// Drops the cache's strong references and every key (scenes alive keep their geometry), and
/// zeroes the counters: the next build of anything is a fresh one.
void ClearGeometryCache();

/// The mesh of `key`: the cached one if a scene or the recent-use list still holds it, else
/// MeshGeometry(build(), key) (built once even when several threads ask for the same key at once;
/// after an exception from `build` nothing is cached, and a thread that waited builds it itself).
std::shared_ptr<const MeshGeometry> CachedMesh(const GeometryKey &key, const std::function<TriangleMesh()> &build);

/// A thread-safe cache of immutable values by key (see the file comment). `bytes` estimates an
/// entry's memory for the strong-reference budget.
template <class T>
class SharedCache {
  public:
    SharedCache(std::size_t budgetBytes, std::function<std::size_t(const T &)> bytes)
        : budget_(budgetBytes), bytes_(std::move(bytes)) {}

    /// The value of `key`, or the one `build()` returns (a shared_ptr<const T>), stored under it.
    template <class Build>
    std::shared_ptr<const T> GetOrBuild(const std::string &key, Build &&build) {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            Entry &e = entries_[key];
            if (std::shared_ptr<const T> v = e.value.lock()) {
                ++reuses_;
                Touch(key, v);
                return v;
            }
            if (!e.building) break;
            built_.wait(lock);  // another thread builds this key: take its result (or retry)
        }
        entries_[key].building = true;
        lock.unlock();
        std::shared_ptr<const T> v;
        try {
            v = build();
        } catch (...) {
            lock.lock();
            entries_.erase(key);
            built_.notify_all();
            throw;
        }
        lock.lock();
        Entry &e = entries_[key];
        e.building = false;
        e.value = v;
        ++builds_;
        Touch(key, v);
        built_.notify_all();
        return v;
    }
    long long Builds() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return builds_;
    }
    long long Reuses() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return reuses_;
    }
    /// Forgets every key not being built and the strong references; zeroes the counters.
    void Clear() {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto it = entries_.begin(); it != entries_.end();)
            it = it->second.building ? std::next(it) : entries_.erase(it);
        recent_.clear();
        recentBytes_ = 0;
        builds_ = reuses_ = 0;
    }

  private:
    struct Entry {
        std::weak_ptr<const T> value;
        bool building = false;
    };
    struct Recent {
        std::string key;
        std::shared_ptr<const T> value;
        std::size_t bytes;
    };
    /// Moves `key` to the front of the recent-use list, then drops the oldest strong references
    /// beyond the budget (an entry larger than the whole budget is not kept strongly). Locked.
    void Touch(const std::string &key, const std::shared_ptr<const T> &v) {
        for (auto it = recent_.begin(); it != recent_.end(); ++it)
            if (it->key == key) {
                recentBytes_ -= it->bytes;
                recent_.erase(it);
                break;
            }
        const std::size_t b = bytes_(*v);
        recent_.push_front(Recent{key, v, b});
        recentBytes_ += b;
        while (!recent_.empty() && recentBytes_ > budget_) {
            recentBytes_ -= recent_.back().bytes;
            recent_.pop_back();
        }
        // Keys whose value has died (no scene, no recent use) are forgotten.
        for (auto it = entries_.begin(); it != entries_.end();)
            it = !it->second.building && it->second.value.expired() ? entries_.erase(it) : std::next(it);
    }

    mutable std::mutex mutex_;
    std::condition_variable built_;
    std::unordered_map<std::string, Entry> entries_;
    std::list<Recent> recent_;  // most recent first
    std::size_t recentBytes_ = 0;
    const std::size_t budget_;
    const std::function<std::size_t(const T &)> bytes_;
    long long builds_ = 0, reuses_ = 0;
};

}  // namespace phasor
