// The joints of a distributed run (parallel/distributed.hpp JointShare, theory §9,
// docs/parallel.md "Joints"): the history of the joints each process sums, to every process.
#include <algorithm>
#include <cstring>

#include "parallel/distributed.hpp"

namespace fdem {

namespace {

// One joint's history as bytes: id, then every per-joint array of JointState (the per-mode
// history only where the model has it), in the order of fields()
class JointRecords {
public:
    // (js of a model with joints: joint 0 exists)
    explicit JointRecords(const JointState& js) : mixed_(!js.dn_max.empty()) {
        fields(js, 0, [&](const auto& v) { bytes_ += sizeof v; });
    }

    void pack(const JointState& js, int32_t j, std::vector<char>& out) const {
        const size_t at = out.size();
        out.resize(at + bytes_);
        char* p = out.data() + at;
        std::memcpy(p, &j, sizeof j);
        p += sizeof j;
        fields(js, static_cast<size_t>(j), [&](const auto& v) {
            std::memcpy(p, &v, sizeof v);
            p += sizeof v;
        });
    }

    // the records in [p, end) into js
    void unpack(JointState& js, const char* p, const char* end) const {
        while (p < end) {
            int32_t j = 0;
            std::memcpy(&j, p, sizeof j);
            p += sizeof j;
            fields(js, static_cast<size_t>(j), [&](auto& v) {
                std::memcpy(&v, p, sizeof v);
                p += sizeof v;
            });
        }
    }

private:
    // fn(field) for every per-joint field of joint k (JointState or const JointState)
    template <class JS, class Fn>
    void fields(JS& js, size_t k, Fn fn) const {
        fn(js.d_max[k]);
        fn(js.z_max[k]);
        if (mixed_) {
            fn(js.dn_max[k]);
            fn(js.ds_max[k]);
            fn(js.an_min[k]);
            fn(js.as_min[k]);
        }
        fn(js.status[k]);
        fn(js.mode_bits[k]);
        fn(js.mode[k]);
        fn(js.break_step[k]);
        fn(js.work[k]);
        fn(js.f_prev[k]);
        fn(js.d_prev[k]);
    }
    bool mixed_;
    size_t bytes_ = sizeof(int32_t);
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
