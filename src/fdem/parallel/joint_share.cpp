// The joints of a distributed run (parallel/distributed.hpp JointShare, theory §9,
// docs/parallel.md "Joints"): the history of the joints each process sums, to every process.
#include <algorithm>
#include <array>
#include <cstring>

#include "parallel/distributed.hpp"

namespace fdem {

namespace {

// One joint's history as bytes: id, then every per-joint array of JointState (the per-mode
// history only where the model has it)
class JointRecords {
public:
    explicit JointRecords(const JointState& js) : mixed_(!js.dn_max.empty()) {}

    size_t bytes() const {
        return sizeof(int32_t) + 2 * sizeof(Real3) + (mixed_ ? 4 * sizeof(Real3) : 0) +
               3 * sizeof(uint8_t) + sizeof(int64_t) + sizeof(Real) + 2 * sizeof(Real4);
    }

    void pack(const JointState& js, int32_t j, std::vector<char>& out) const {
        const size_t at = out.size();
        out.resize(at + bytes());
        char* p = out.data() + at;
        const auto k = static_cast<size_t>(j);
        put(p, j);
        put(p, js.d_max[k]);
        put(p, js.z_max[k]);
        if (mixed_) {
            put(p, js.dn_max[k]);
            put(p, js.ds_max[k]);
            put(p, js.an_min[k]);
            put(p, js.as_min[k]);
        }
        put(p, js.status[k]);
        put(p, js.mode_bits[k]);
        put(p, js.mode[k]);
        put(p, js.break_step[k]);
        put(p, js.work[k]);
        put(p, js.f_prev[k]);
        put(p, js.d_prev[k]);
    }

    // the records in [p, end) into js
    void unpack(JointState& js, const char* p, const char* end) const {
        while (p < end) {
            int32_t j = 0;
            get(p, j);
            const auto k = static_cast<size_t>(j);
            get(p, js.d_max[k]);
            get(p, js.z_max[k]);
            if (mixed_) {
                get(p, js.dn_max[k]);
                get(p, js.ds_max[k]);
                get(p, js.an_min[k]);
                get(p, js.as_min[k]);
            }
            get(p, js.status[k]);
            get(p, js.mode_bits[k]);
            get(p, js.mode[k]);
            get(p, js.break_step[k]);
            get(p, js.work[k]);
            get(p, js.f_prev[k]);
            get(p, js.d_prev[k]);
        }
    }

private:
    using Real3 = std::array<Real, 3>;
    using Real4 = std::array<Real, 4>;
    template <class T>
    static void put(char*& p, const T& v) {
        std::memcpy(p, &v, sizeof v);
        p += sizeof v;
    }
    template <class T>
    static void get(const char*& p, T& v) {
        std::memcpy(&v, p, sizeof v);
        p += sizeof v;
    }
    bool mixed_;
};

// every process's records (its counted chunks' joints for which keep(j)) on every process
template <class Keep>
void share_records(const Model& m, State& s, const StepPlan& p, const Comm& comm, Keep keep) {
    const Joints& J = m.joints;
    JointState& js = s.joints;
    const JointRecords rec(js);
    const JointSubset& sub = p.joints.subset;
    std::vector<char>& mine = p.joints.bytes;
    mine.clear();
    for (size_t k = 0; k < sub.chunks.size(); ++k) {
        if (!sub.counts[k]) continue;
        const int32_t b = sub.chunks[k] * kJointChunk;
        const int32_t e = std::min(J.num_joints(), b + kJointChunk);
        for (int32_t j = b; j < e; ++j) {
            if (keep(j)) rec.pack(js, j, mine);
        }
    }
    comm.allgather_bytes(mine, p.joints.all);
    rec.unpack(js, p.joints.all.data(), p.joints.all.data() + p.joints.all.size());
}

}  // namespace

void gather_joint_state(const Model& m, State& s, const StepPlan& p, const Comm& comm) {
    if (m.joints.nodes.empty()) return;
    share_records(m, s, p, comm, [](int32_t) { return true; });
    // the work of every process since the last energy step (exact: any grouping, same bits)
    ExactSum w = p.joints.work;
    comm.sum(w);
    p.joints.work.clear();
    s.joints.total_work_sum.add(w);
    s.joints.total_work = s.joints.total_work_sum.value();
}

void share_breaks(const Model& m, State& s, const StepPlan& p, const Comm& comm) {
    const int64_t step = s.step;
    const int64_t* bs = s.joints.break_step.data();
    share_records(m, s, p, comm, [&](int32_t j) { return bs[j] == step; });
}

}  // namespace fdem
