// SPDX-License-Identifier: Apache-2.0
// phasor — the processes of one run under MPI (distributed.h; docs/distributed.md). Plain MPI-3.
//
// Work is shared in phases (one sampling render, one batch of rs's field, one set of whole units):
// rank 0 runs a server thread that hands items to the other ranks on request and takes their
// results back, while its own threads take items from the same source; every other rank runs a
// client thread that keeps a few items queued for its threads and sends the results. Only these
// threads call MPI during a phase and the main thread only outside one (MPI_THREAD_SERIALIZED).
// Every wait polls with non-blocking calls and short sleeps, so a waiting rank does not spin on a
// core its render threads need. Every rank makes the same sequence of phases (they run the same
// command on the same scene), and each phase has its own tag, so messages of consecutive phases
// never mix.
#include <fcntl.h>
#include <mpi.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <iostream>
#include <list>
#include <mutex>
#include <thread>

#include <tbb/global_control.h>

#include "app/bytes.h"
#include "app/distributed.h"
#include "app/render_common.h"
#include "core/diagnostics.h"

namespace phasor::dist {
namespace {

bool gMpi = false;  // MPI_Init was called here
int gRank = 0, gSize = 1, gNode = 1, gThreads = 0;
int gPhase = 0;  // phases begun so far (the same sequence on every rank)

constexpr int ControlTag = 1;  // AllOk's message
int NextTag() { return 100 + (gPhase++ % 30000); }  // MPI guarantees tags up to 32767

int gErr = 2;  // where a rank other than 0 reports a fatal error (its stderr before Start silenced it)

// Sleeps between the polls of a one-off wait (a collective, the last sends of a phase): 50 µs,
// doubling up to `cap` µs.
class Idle {
  public:
    int Next(int cap) {
        const int us = std::min(us_, cap);
        us_ = std::min(us_ * 2, 2000);
        return us;
    }
    void Wait(int cap = 2000) { std::this_thread::sleep_for(std::chrono::microseconds(Next(cap))); }

  private:
    int us_ = 50;
};
// The longest poll intervals [µs]: rank 0's server while items are out or asked for (a helper rank
// keeps ≥ SlackSeconds of work queued, so an answer within a millisecond is in time); a helper's
// client while it waits for items and has none queued; either while a message it receives is part-way between
// two ranks (it moves only as both sides call MPI).
constexpr int ServingUs = 1000;
constexpr int AwaitingUs = 100;
constexpr int InFlightUs = 20;
constexpr std::size_t MessageBytes = 32000;  // the largest message of several items
constexpr int IdleUs = 2000;  // otherwise: a stop or the end of a phase still arrives within 2 ms
constexpr double SlackSeconds = 0.008;

void WaitFor(MPI_Request &r) {
    Idle idle;
    for (int done = 0;;) {
        MPI_Test(&r, &done, MPI_STATUS_IGNORE);
        if (done) return;
        idle.Wait();
    }
}

// ---- messages -------------------------------------------------------------------------------------
// Every message of a phase is bytes whose first byte says what it is.
enum : char {
    MsgRequest = 1,  // → 0: int32 items wanted
    MsgResult,       // → 0: one item's result
    MsgStopped,      // → 0: int32 signal: this rank was stopped by a signal
    MsgAckEnd,       // → 0: this rank is out of the phase
    MsgItems,        // 0 →: int32 count, then (int32 length, bytes) per item
    MsgStop,         // 0 →: stop rendering (the phase ends soon)
    MsgEnd,          // 0 →: the phase is over
};

using Bytes = std::string;

// One phase's traffic on one thread: non-blocking sends kept until complete, and non-blocking
// receives of matched messages (MPI_Improbe + MPI_Imrecv), handed over in the order they were
// matched once complete. Nothing here blocks: a large message moves in several steps (Open MPI's
// rendezvous: both sides must call MPI for it to progress), and a blocking receive would spin on
// a core the render threads need until the sender's thread next wakes up. While a receive is
// incomplete the owner polls again soon (Receiving). A send's completion waits for the receiver
// (its next poll), not for us, so pending sends need no faster polling: messages are kept to at
// most MessageBytes (Open MPI's shared-memory transport sends that much with the message's
// header, so the data needs no later step from the sender).
class Channel {
  public:
    explicit Channel(int tag) : tag_(tag) {}
    ~Channel() { Drain(); }
    void Send(int to, Bytes &&bytes) {
        sends_.push_back({std::move(bytes), MPI_REQUEST_NULL, to});
        Transfer &o = sends_.back();
        MPI_Isend(o.data.data(), int(o.data.size()), MPI_BYTE, to, tag_, MPI_COMM_WORLD, &o.request);
    }
    void Send(int to, char type) { Send(to, Bytes(1, type)); }
    /// The next complete message of this phase from `from` (MPI_ANY_SOURCE: anyone), in the order
    /// of arrival, if there is one.
    bool Receive(int from, int *source, Bytes *bytes) {
        for (;;) {  // start receiving everything that has arrived
            int flag = 0;
            MPI_Message message;
            MPI_Status st;
            MPI_Improbe(from, tag_, MPI_COMM_WORLD, &flag, &message, &st);
            if (!flag) break;
            int count = 0;
            MPI_Get_count(&st, MPI_BYTE, &count);
            receives_.push_back({Bytes(std::size_t(count), '\0'), MPI_REQUEST_NULL, st.MPI_SOURCE});
            Transfer &in = receives_.back();
            MPI_Imrecv(in.data.data(), count, MPI_BYTE, &message, &in.request);
        }
        if (receives_.empty()) return false;
        int done = 0;
        MPI_Test(&receives_.front().request, &done, MPI_STATUS_IGNORE);
        if (!done) return false;
        *source = receives_.front().peer;
        *bytes = std::move(receives_.front().data);
        receives_.pop_front();
        return true;
    }
    void Progress() {
        for (auto it = sends_.begin(); it != sends_.end();) {
            int done = 0;
            MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
            it = done ? sends_.erase(it) : std::next(it);
        }
    }
    /// A send or a receive has started and not completed: it needs this thread's next poll.
    bool Receiving() const { return !receives_.empty(); }
    void Drain() {
        Idle idle;
        for (Progress(); !sends_.empty(); Progress()) idle.Wait(InFlightUs);
        for (Transfer &in : receives_) {  // matched and not taken (a phase that ended early)
            for (int done = 0; MPI_Test(&in.request, &done, MPI_STATUS_IGNORE), !done;) idle.Wait(InFlightUs);
        }
        receives_.clear();
    }

  private:
    struct Transfer {
        Bytes data;
        MPI_Request request;
        int peer;
    };
    int tag_;
    std::list<Transfer> sends_;
    std::deque<Transfer> receives_;
};

// Rank 0's side of a phase, on its own thread: answers the other ranks' requests with items from
// `next` (false: none now), hands their results to `result`, relays a stop (`stop` set here, or a
// rank reporting a signal) to every rank, and after Finish() ends the phase on every rank.
class Server {
  public:
    using Next = std::function<bool(Bytes &)>;
    using Result = std::function<void(int source, ByteReader &)>;
    Server(int tag, std::atomic<bool> *stop, std::atomic<int> *signal, Next next, Result result)
        : tag_(tag), stop_(stop), signal_(signal), next_(std::move(next)), result_(std::move(result)) {
        thread_ = std::thread([this] { Run(); });
    }
    ~Server() { Finish(); }
    /// Ends the phase (every rank acknowledges) and joins the thread. No callback runs afterwards.
    void Finish() {
        if (!thread_.joinable()) return;
        finish_.store(true);
        thread_.join();
    }

  private:
    void Run() {
        Channel ch(tag_);
        std::vector<int> want(std::size_t(gSize), 0);
        bool stopSent = false, endSent = false;
        int acks = 0;
        long long out = 0;  // items handed to other ranks and not back yet
        for (;;) {
            bool busy = false;
            int src = 0;
            Bytes m;
            while (ch.Receive(MPI_ANY_SOURCE, &src, &m)) {
                busy = true;
                ByteReader r(m);
                switch (r.Get<char>()) {
                    case MsgRequest: want[std::size_t(src)] += r.Get<int32_t>(); break;
                    case MsgResult:
                        --out;
                        if (!endSent) result_(src, r);  // after the end (an aborted phase) nobody takes it
                        break;
                    case MsgStopped: {
                        const int sig = r.Get<int32_t>();
                        int none = 0;
                        if (signal_) signal_->compare_exchange_strong(none, sig);
                        if (stop_) stop_->store(true);
                        break;
                    }
                    case MsgAckEnd: ++acks; break;
                    default: break;
                }
            }
            if (stop_ && stop_->load() && !stopSent && !endSent) {
                for (int w = 1; w < gSize; ++w) ch.Send(w, MsgStop);
                stopSent = busy = true;
            }
            if (!endSent)
                for (int w = 1; w < gSize; ++w) {
                    // The items a rank asked for, in messages of at most MessageBytes unless one
                    // item is larger.
                    ByteWriter items;
                    int32_t count = 0;
                    auto send = [&] {
                        if (count == 0) return;
                        out += count;
                        std::memcpy(items.bytes.data() + 1, &count, sizeof count);
                        ch.Send(w, std::move(items.bytes));
                        items = ByteWriter();
                        count = 0;
                        busy = true;
                    };
                    for (Bytes item; want[std::size_t(w)] > 0 && next_(item); --want[std::size_t(w)]) {
                        if (count > 0 && items.bytes.size() + sizeof(int32_t) + item.size() > MessageBytes) send();
                        if (count == 0) {
                            items.Put(MsgItems);
                            items.Put(count);
                        }
                        items.Put(int32_t(item.size()));
                        items.PutBytes(item.data(), item.size());
                        ++count;
                    }
                    send();
                }
            if (finish_.load() && !endSent) {
                for (int w = 1; w < gSize; ++w) ch.Send(w, MsgEnd);
                endSent = busy = true;
            }
            if (endSent && acks == gSize - 1) break;
            ch.Progress();
            const bool awaiting = out > 0 || std::any_of(want.begin(), want.end(), [](int w) { return w > 0; });
            // Poll again at once after activity, else after an interval fixed by what is pending:
            // a rank's work queue holds SlackSeconds, so no shorter interval is needed (each wake-up
            // of this thread takes the core from one of rank 0's render threads).
            if (!busy)
                std::this_thread::sleep_for(
                    std::chrono::microseconds(ch.Receiving() ? InFlightUs : awaiting ? ServingUs : IdleUs));
        }
        ch.Drain();
    }

    int tag_;
    std::atomic<bool> *stop_;
    std::atomic<int> *signal_;
    Next next_;
    Result result_;
    std::atomic<bool> finish_{false};
    std::thread thread_;
};

// Another rank's side of a phase, on its own thread: keeps at least `depth` items in hand (queued or
// being worked on) — with `workers` > 0, as many more as this rank's `workers` threads finish in
// SlackSeconds (measured as results come in), so that short items do not starve it while rank 0's
// server sleeps between polls —, sends results, stops on rank 0's word (`stop` set) and reports its
// own stop (`localStop` set: MsgStopped with the signal) so that rank 0 stops everyone.
class Client {
  public:
    Client(int tag, int depth, std::atomic<bool> *stop, const std::atomic<bool> *localStop, int workers = 0)
        : tag_(tag), depth_(depth), workers_(workers), stop_(stop), localStop_(localStop) {
        thread_ = std::thread([this] { Run(); });
    }
    ~Client() {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            if (!ended_) {
                // Left before rank 0 ended the phase (an exception on this rank): the other ranks
                // would wait for it for ever.
                lock.unlock();
                const std::string msg =
                    "phasor: rank " + std::to_string(gRank) + " failed during a distributed render; aborting the job\n";
                ssize_t ignored = ::write(gErr, msg.data(), msg.size());
                (void)ignored;
                MPI_Abort(MPI_COMM_WORLD, 2);
            }
        }
        thread_.join();
    }
    /// The next item (blocks until one arrives); false once the phase is over.
    bool Next(Bytes &item) {
        std::unique_lock<std::mutex> lock(mutex_);
        if (queue_.empty()) {  // starving: the client thread asks for more at once
            event_ = true;
            wake_.notify_one();
        }
        cv_.wait(lock, [&] { return !queue_.empty() || ended_; });
        if (queue_.empty()) return false;
        item = std::move(queue_.front());
        queue_.pop_front();
        ++working_;
        return true;
    }
    /// The result of an item Next gave.
    void Done(Bytes &&result) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            results_.push_back(std::move(result));
            --working_;
            event_ = true;
            const auto now = std::chrono::steady_clock::now();
            if (workers_ > 0 && lastDone_ != std::chrono::steady_clock::time_point{}) {
                // Items this rank finishes per second, smoothed over ~16 results.
                const double dt = std::chrono::duration<double>(now - lastDone_).count();
                interval_ = interval_ > 0 ? interval_ + (dt - interval_) / 16 : dt;
            }
            lastDone_ = now;
        }
        wake_.notify_one();
    }

  private:
    void Run() {
        Channel ch(tag_);
        int requested = 0;  // asked for and not received yet
        bool stoppedSent = false, ended = false;
        while (!ended) {
            bool busy = false;
            int src = 0;
            Bytes m;
            while (!ended && ch.Receive(0, &src, &m)) {
                busy = true;
                ByteReader r(m);
                switch (r.Get<char>()) {
                    case MsgItems: {
                        const int32_t count = r.Get<int32_t>();
                        std::lock_guard<std::mutex> lock(mutex_);
                        for (int32_t i = 0; i < count; ++i) {
                            Bytes item(std::size_t(r.Get<int32_t>()), '\0');
                            r.GetBytes(item.data(), item.size());
                            queue_.push_back(std::move(item));
                        }
                        requested -= count;
                        cv_.notify_all();
                        break;
                    }
                    case MsgStop:
                        if (stop_) stop_->store(true);
                        break;
                    case MsgEnd: ended = true; break;
                    default: break;
                }
            }
            std::deque<Bytes> results;
            int inHand = 0, queued = 0, depth = depth_;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                results.swap(results_);
                queued = int(queue_.size());
                inHand = queued + working_;
                if (workers_ > 0 && interval_ > 0)
                    depth = std::max(depth_, workers_ + std::min(MaxSlackItems, int(SlackSeconds / interval_) + 1));
            }
            if (!ended) {
                for (Bytes &r : results) ch.Send(0, std::move(r));
                busy |= !results.empty();
                if (localStop_ && localStop_->load() && !stoppedSent) {
                    ByteWriter w;
                    w.Put(MsgStopped);
                    w.Put(int32_t(StopSignal()));
                    ch.Send(0, std::move(w.bytes));
                    stoppedSent = busy = true;
                }
                const int want = depth - inHand - requested;
                if (want > 0 && !(stop_ && stop_->load())) {
                    ByteWriter w;
                    w.Put(MsgRequest);
                    w.Put(int32_t(want));
                    ch.Send(0, std::move(w.bytes));
                    requested += want;
                    busy = true;
                }
            }
            ch.Progress();
            // Wait for this rank's threads (a result, a starving thread) or the next poll: short
            // while items are asked for, else long (a stop or the end still arrive within 2 ms).
            const int us = busy               ? 0
                           : ch.Receiving()   ? InFlightUs
                           : requested > 0 && queued == 0 ? AwaitingUs
                                                          : IdleUs;
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait_for(lock, std::chrono::microseconds(us), [&] { return event_; });
            event_ = false;
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            ended_ = true;
            queue_.clear();
        }
        cv_.notify_all();
        ch.Send(0, MsgAckEnd);
        ch.Drain();
    }

    static constexpr int MaxSlackItems = 256;
    int tag_, depth_, workers_;
    std::chrono::steady_clock::time_point lastDone_{};
    double interval_ = 0;  // seconds between results, smoothed
    std::atomic<bool> *stop_;
    const std::atomic<bool> *localStop_;
    std::mutex mutex_;
    std::condition_variable cv_, wake_;
    std::deque<Bytes> queue_, results_;
    int working_ = 0;
    bool ended_ = false, event_ = false;
    std::thread thread_;
};

// A server's items that are indices (rs's batches, whole units): the next from `take` (< 0: none now).
Server::Next IndexItems(std::function<int()> take) {
    return [take = std::move(take)](Bytes &item) {
        const int u = take();
        if (u < 0) return false;
        ByteWriter w;
        w.Put(int32_t(u));
        item = std::move(w.bytes);
        return true;
    };
}

// ---- tiles as bytes -------------------------------------------------------------------------------

// A pixel's accumulators as sent: without Stokes output its Stokes means (all zero) stay behind,
// 56 bytes instead of 96.
constexpr std::size_t PixelBytes(bool stokes) {
    return stokes ? sizeof(Film::PixelState) : offsetof(Film::PixelState, stokes);
}

void PutTile(ByteWriter &w, const TileTask &t, bool stokes) {
    for (int v : {t.tile, t.x0, t.y0, t.x1, t.y1, t.sampleEnd}) w.Put(int32_t(v));
    w.Put(int64_t(t.rays));
    for (long long n : t.counters.n) w.Put(int64_t(n));
    w.Put(int64_t(t.pixels.size()));
    for (const Film::PixelState &p : t.pixels) w.PutBytes(&p, PixelBytes(stokes));
}

void GetTile(ByteReader &r, TileTask &t, bool stokes) {
    int32_t v[6];
    for (int32_t &x : v) x = r.Get<int32_t>();
    t.tile = v[0], t.x0 = v[1], t.y0 = v[2], t.x1 = v[3], t.y1 = v[4], t.sampleEnd = v[5];
    t.rays = r.Get<int64_t>();
    for (long long &n : t.counters.n) n = r.Get<int64_t>();
    const int64_t count = r.Get<int64_t>();
    if (count != int64_t(t.x1 - t.x0) * (t.y1 - t.y0)) throw Error("internal error: a malformed tile between MPI ranks");
    t.pixels.assign(std::size_t(count), Film::PixelState{});
    for (Film::PixelState &p : t.pixels) r.GetBytes(&p, PixelBytes(stokes));
}

// A helper rank's tiles: from its client, back through it.
class RemoteTiles final : public TileSource {
  public:
    /// `threads`: this rank's render threads (it keeps ≥ threads + 2 tiles in hand, more when tiles
    /// are short: Client).
    RemoteTiles(int tag, int threads, bool stokes, std::atomic<bool> *stop, const std::atomic<bool> *localStop)
        : stokes_(stokes), client_(tag, threads + 2, stop, localStop, threads) {}
    bool Next(TileTask &task) override {
        Bytes b;
        if (!client_.Next(b)) return false;
        ByteReader r(b);
        GetTile(r, task, stokes_);
        return true;
    }
    void Done(TileTask &task) override {
        ByteWriter w;
        w.Put(MsgResult);
        PutTile(w, task, stokes_);
        client_.Done(std::move(w.bytes));
    }

  private:
    bool stokes_;
    Client client_;
};

class MpiShare final : public Share {
  public:
    explicit MpiShare(const std::atomic<bool> *cancel) : cancel_(cancel) {
        // The caller's flag (a signal, a time budget) becomes this render's stop on this rank.
        watch_ = std::thread([this] {
            while (!quit_.load()) {
                if (cancel_ && cancel_->load() && !localStop_.load()) {
                    localStop_.store(true);
                    stop_.store(true);
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
            }
        });
    }
    ~MpiShare() override {
        server_.reset();
        tiles_.reset();
        quit_.store(true);
        watch_.join();
    }
    bool Coordinates() const override { return gRank == 0; }
    const std::atomic<bool> *Stop() const override { return &stop_; }
    int Signal() const override { return signal_.load(); }
    std::vector<long long> WorkByRank() const override {
        std::lock_guard<std::mutex> lock(countMutex_);
        return byRank_;
    }

    void BeginTiles(TilePasses &passes) override {
        passes_ = &passes;
        const bool stokes = passes.GetFilm().HasStokes();
        server_ = std::make_unique<Server>(
            NextTag(), &stop_, &signal_,
            [&passes, stokes](Bytes &item) {
                TileTask t;
                if (!passes.Next(t)) return false;
                ByteWriter w;
                PutTile(w, t, stokes);
                item = std::move(w.bytes);
                return true;
            },
            [this, &passes, stokes](int source, ByteReader &r) {
                TileTask t;
                GetTile(r, t, stokes);
                passes.Done(t);
                Count(source, 1);
            });
    }
    void EndTiles() override {
        server_.reset();
        // Rank 0's own tiles: every tile taken back that came from no other rank.
        long long remote = 0;
        for (long long c : WorkByRank()) remote += c;
        if (passes_) Count(0, passes_->TilesDone() - remote);
        passes_ = nullptr;
    }
    TileSource *HelperTiles(Film &film) override {
        // Enough tiles in hand that each render thread finds the next one waiting while the next
        // request is answered (a 1-spp tile of a showcase scene takes ~1 ms; rank 0 answers within
        // ServingUs): RemoteTiles keeps SlackSeconds of this rank's work queued.
        const int threads =
            int(std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
        tiles_ = std::make_unique<RemoteTiles>(NextTag(), threads, film.HasStokes(), &stop_, &localStop_);
        return tiles_.get();
    }

    bool Batches(std::vector<double> &values, int units, const BatchFunction &compute,
                 const std::function<bool(int)> &done, const std::atomic<bool> *) override {
        const std::size_t n = values.size();
        const int tag = NextTag();
        if (gRank != 0) {
            Client client(tag, 2, &stop_, &localStop_);
            for (Bytes item; client.Next(item);) {
                ByteReader r(item);
                const int u = r.Get<int32_t>();
                const std::size_t b = BatchBegin(n, units, u), e = BatchBegin(n, units, u + 1);
                compute(b, e);
                ByteWriter w;
                w.Put(MsgResult);
                w.Put(int32_t(u));
                w.PutBytes(values.data() + b, (e - b) * sizeof(double));
                client.Done(std::move(w.bytes));
            }
            return false;
        }
        std::mutex m;
        std::condition_variable cv;
        int next = 0, finished = 0;
        auto take = [&]() {
            std::lock_guard<std::mutex> lock(m);
            return stop_.load() || next >= units ? -1 : next++;
        };
        Server server(
            tag, &stop_, &signal_, IndexItems(take),
            [&](int source, ByteReader &r) {
                const int u = r.Get<int32_t>();
                if (stop_.load() || u < 0 || u >= units) return;  // a stopped rank's batch is incomplete
                Count(source, 1);
                const std::size_t b = BatchBegin(n, units, u), e = BatchBegin(n, units, u + 1);
                r.GetBytes(values.data() + b, (e - b) * sizeof(double));
                std::lock_guard<std::mutex> lock(m);
                ++finished;
                cv.notify_all();
            });
        int reported = 0;
        for (;;) {
            const int u = take();
            if (u >= 0) {
                compute(BatchBegin(n, units, u), BatchBegin(n, units, u + 1));
                Count(0, 1);
                std::lock_guard<std::mutex> lock(m);
                if (!stop_.load()) ++finished;
            }
            int f;
            {
                std::unique_lock<std::mutex> lock(m);
                if (u < 0 && finished < units && !stop_.load())
                    cv.wait_for(lock, std::chrono::milliseconds(20));
                f = finished;
            }
            while (reported < f && !stop_.load())
                if (done && !done(++reported)) stop_.store(true);
            if (stop_.load() || f == units) break;
        }
        server.Finish();
        return !stop_.load() && finished == units;
    }

  private:
    void Count(int rank, long long n) {
        std::lock_guard<std::mutex> lock(countMutex_);
        byRank_[std::size_t(rank)] += n;
    }

    const std::atomic<bool> *cancel_;
    mutable std::mutex countMutex_;
    std::vector<long long> byRank_ = std::vector<long long>(static_cast<std::size_t>(gSize), 0);
    TilePasses *passes_ = nullptr;
    std::atomic<bool> stop_{false}, localStop_{false}, quit_{false};
    std::atomic<int> signal_{0};
    std::thread watch_;
    std::unique_ptr<Server> server_;
    std::unique_ptr<RemoteTiles> tiles_;
};

// Whether the environment says an MPI launcher started this process.
bool LaunchedByMpi() {
    if (const char *force = std::getenv("PHASOR_MPI")) {
        if (std::strcmp(force, "0") == 0) return false;
        if (std::strcmp(force, "1") == 0) return true;
    }
    for (const char *v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(v)) return true;
    return false;
}

// Threads per rank: the cores this rank may run on, shared with the ranks of its node that are
// bound to the same cores.
int ThreadsPerRank(MPI_Comm node) {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
    const int mine = CPU_COUNT(&set);
    uint64_t h = 1469598103934665603ull;  // FNV-1a of the mask
    for (std::size_t i = 0; i < sizeof set; ++i) h = (h ^ reinterpret_cast<const unsigned char *>(&set)[i]) * 1099511628211ull;
    std::vector<uint64_t> all(static_cast<std::size_t>(gNode));
    MPI_Allgather(&h, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, node);
    const int same = int(std::count(all.begin(), all.end(), h));
    return std::max(1, mine / std::max(1, same));
}

}  // namespace

bool Available() { return true; }

bool Start(int &argc, char **&argv) {
    if (!LaunchedByMpi()) return true;
    // Open MPI's shared-memory transport sends messages above 4 KB in two steps, the second only
    // when the sender's thread next calls MPI; a tile's message (≤ MessageBytes) then waits for
    // rank 0's server to wake up. Sending up to 32 KB at once makes every tile one step. A value
    // the user set is kept; other MPI libraries ignore these names.
    for (const char *name : {"OMPI_MCA_btl_vader_eager_limit", "OMPI_MCA_btl_sm_eager_limit"})
        ::setenv(name, "32768", 0);
    int provided = 0;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
        std::fprintf(stderr, "error: MPI could not be started\n");
        return false;
    }
    gMpi = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &gRank);
    MPI_Comm_size(MPI_COMM_WORLD, &gSize);
    if (provided < MPI_THREAD_SERIALIZED) {
        if (gRank == 0)
            std::fprintf(stderr, "error: this MPI library gives no MPI_THREAD_SERIALIZED support, which phasor needs\n");
        return false;
    }
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, gRank, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &gNode);
    gThreads = gSize > 1 ? ThreadsPerRank(node) : 0;
    MPI_Comm_free(&node);
    if (gRank != 0) {  // one voice: rank 0's (the other ranks' output, libraries' included, goes nowhere)
        std::fflush(nullptr);
        gErr = ::dup(2);
        const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (null >= 0) {
            ::dup2(null, 1);
            ::dup2(null, 2);
            ::close(null);
        }
    }
    return true;
}

void Finish() {
    if (!gMpi) return;
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
    gMpi = false;
}

int Rank() { return gRank; }
int Size() { return gSize; }
int RanksOnNode() { return gNode; }
int DefaultThreads() { return gThreads; }

int Agree(int status) {
    if (gSize == 1) return status;
    MPI_Request r;
    MPI_Ibcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD, &r);
    WaitFor(r);
    return status;
}

bool AllOk(bool ok, const std::string &message, std::string *failure) {
    if (gSize == 1) return ok;
    int mine = ok ? 1 : 0;
    std::vector<int> all(static_cast<std::size_t>(gSize));
    MPI_Request r;
    MPI_Iallgather(&mine, 1, MPI_INT, all.data(), 1, MPI_INT, MPI_COMM_WORLD, &r);
    WaitFor(r);
    const auto bad = std::find(all.begin(), all.end(), 0);
    if (bad == all.end()) return true;
    const int first = int(bad - all.begin());
    if (first == 0) return false;  // rank 0 failed: it has said why
    // The first failing rank tells rank 0 why (rank 0 loaded the same scene without error: a file
    // missing on that node, say).
    if (gRank == first) {
        MPI_Request s;
        MPI_Isend(message.data(), int(message.size()), MPI_CHAR, 0, ControlTag, MPI_COMM_WORLD, &s);
        WaitFor(s);
    } else if (gRank == 0) {
        MPI_Status st;
        int flag = 0;
        Idle idle;
        for (; MPI_Iprobe(first, ControlTag, MPI_COMM_WORLD, &flag, &st), !flag;) idle.Wait();
        int count = 0;
        MPI_Get_count(&st, MPI_CHAR, &count);
        std::string text(std::size_t(count), '\0');
        MPI_Recv(text.data(), count, MPI_CHAR, first, ControlTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (failure) *failure = "rank " + std::to_string(first) + ": " + text;
    }
    return false;
}

void Broadcast(std::string &text) {
    if (gSize == 1) return;
    long long n = (long long)text.size();
    MPI_Request r;
    MPI_Ibcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD, &r);
    WaitFor(r);
    text.resize(std::size_t(n));
    MPI_Ibcast(text.data(), int(n), MPI_CHAR, 0, MPI_COMM_WORLD, &r);
    WaitFor(r);
}

std::unique_ptr<Share> MakeShare(const std::atomic<bool> *cancel) {
    if (gSize == 1) return nullptr;
    return std::make_unique<MpiShare>(cancel);
}

void ForEachUnit(int units, const std::function<std::string(int)> &compute,
                 const std::function<void(int, std::string &&)> &collect, const std::atomic<bool> *stop) {
    const int tag = NextTag();
    if (gSize == 1 || gRank != 0) {
        if (gSize == 1) {
            for (int u = 0; u < units && !(stop && stop->load()); ++u) collect(u, compute(u));
            return;
        }
        Client client(tag, 1, nullptr, nullptr);
        for (Bytes item; client.Next(item);) {
            ByteReader r(item);
            const int u = r.Get<int32_t>();
            const std::string result = compute(u);
            ByteWriter w;
            w.Put(MsgResult);
            w.Put(int32_t(u));
            w.PutBytes(result.data(), result.size());
            client.Done(std::move(w.bytes));
        }
        return;
    }
    std::mutex m;
    std::condition_variable cv;
    int next = 0, out = 0;
    std::deque<std::pair<int, std::string>> arrived;
    auto take = [&]() {
        std::lock_guard<std::mutex> lock(m);
        if ((stop && stop->load()) || next >= units) return -1;
        ++out;
        return next++;
    };
    Server server(
        tag, nullptr, nullptr, IndexItems(take),
        [&](int, ByteReader &r) {
            const int u = r.Get<int32_t>();
            std::string bytes(r.Left(), '\0');
            r.GetBytes(bytes.data(), bytes.size());
            std::lock_guard<std::mutex> lock(m);
            arrived.emplace_back(u, std::move(bytes));
            cv.notify_all();
        });
    auto collectArrived = [&] {
        for (;;) {
            std::pair<int, std::string> one;
            {
                std::lock_guard<std::mutex> lock(m);
                if (arrived.empty()) return;
                one = std::move(arrived.front());
                arrived.pop_front();
                --out;
            }
            collect(one.first, std::move(one.second));
        }
    };
    for (;;) {
        const int u = take();
        if (u >= 0) {
            std::string result = compute(u);
            {
                std::lock_guard<std::mutex> lock(m);
                --out;
            }
            collect(u, std::move(result));
        }
        collectArrived();
        std::unique_lock<std::mutex> lock(m);
        if (out == 0 && ((stop && stop->load()) || next >= units)) break;
        if (u < 0) cv.wait_for(lock, std::chrono::milliseconds(20));
    }
    server.Finish();
}

}  // namespace phasor::dist
