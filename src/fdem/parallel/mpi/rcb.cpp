// Zoltan RCB: see parallel/mpi/rcb.hpp.
#include "parallel/mpi/rcb.hpp"

#include <zoltan.h>

#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

#include "parallel/distributed.hpp"

namespace fdem {

namespace {

struct Points {
    std::span<const Vec2> x;
    std::span<const double> weight;
    std::span<const uint64_t> gid;
};

int num_obj(void* data, int* ierr) {
    *ierr = ZOLTAN_OK;
    return static_cast<int>(static_cast<Points*>(data)->x.size());
}

void obj_list(void* data, int /*num_gid*/, int /*num_lid*/, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids,
              int wdim, float* wgts, int* ierr) {
    const Points& p = *static_cast<Points*>(data);
    for (size_t i = 0; i < p.x.size(); ++i) {
        gids[i] = static_cast<ZOLTAN_ID_TYPE>(p.gid[i]);
        lids[i] = static_cast<ZOLTAN_ID_TYPE>(i);
        if (wdim > 0) wgts[i] = static_cast<float>(p.weight[i]);
    }
    *ierr = ZOLTAN_OK;
}

int num_geom(void* /*data*/, int* ierr) {
    *ierr = ZOLTAN_OK;
    return 2;
}

void geom_multi(void* data, int /*num_gid*/, int /*num_lid*/, int num_obj_, ZOLTAN_ID_PTR /*gids*/,
                ZOLTAN_ID_PTR lids, int /*num_dim*/, double* geom, int* ierr) {
    const Points& p = *static_cast<Points*>(data);
    for (int k = 0; k < num_obj_; ++k) {
        const Vec2& q = p.x[lids[k]];
        geom[2 * k] = q.x;
        geom[2 * k + 1] = q.y;
    }
    *ierr = ZOLTAN_OK;
}

void check(int rc, const char* what) {
    if (rc != ZOLTAN_OK && rc != ZOLTAN_WARN) {
        throw std::runtime_error(std::string("Zoltan: ") + what + " failed (code " +
                                 std::to_string(rc) + ")");
    }
}

}  // namespace

std::vector<int> rcb_parts(const MpiComm& comm, std::span<const Vec2> x,
                           std::span<const double> weight, std::span<const uint64_t> gid,
                           int parts) {
    if (weight.size() != x.size() || gid.size() != x.size()) {
        throw std::invalid_argument("rcb_parts: x, weight and gid differ in length");
    }
    static const bool initialised = [] {
        float version = 0;
        check(Zoltan_Initialize(0, nullptr, &version), "Zoltan_Initialize");
        return true;
    }();
    (void)initialised;
    Points pts{x, weight, gid};
    Zoltan_Struct* zz = Zoltan_Create(comm.handle());
    if (zz == nullptr) throw std::runtime_error("Zoltan: Zoltan_Create failed");
    const std::string nparts = std::to_string(parts);
    Zoltan_Set_Param(zz, "DEBUG_LEVEL", "0");
    Zoltan_Set_Param(zz, "LB_METHOD", "RCB");
    Zoltan_Set_Param(zz, "NUM_GID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "NUM_LID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "OBJ_WEIGHT_DIM", "1");
    Zoltan_Set_Param(zz, "RETURN_LISTS", "PARTS");
    Zoltan_Set_Param(zz, "NUM_GLOBAL_PARTS", nparts.c_str());
    Zoltan_Set_Param(zz, "DETERMINISTIC", "1");
    Zoltan_Set_Param(zz, "RCB_OUTPUT_LEVEL", "0");
    Zoltan_Set_Num_Obj_Fn(zz, num_obj, &pts);
    Zoltan_Set_Obj_List_Fn(zz, obj_list, &pts);
    Zoltan_Set_Num_Geom_Fn(zz, num_geom, &pts);
    Zoltan_Set_Geom_Multi_Fn(zz, geom_multi, &pts);

    int changes = 0, ngid = 0, nlid = 0, nimp = 0, nexp = 0;
    ZOLTAN_ID_PTR imp_g = nullptr, imp_l = nullptr, exp_g = nullptr, exp_l = nullptr;
    int *imp_p = nullptr, *imp_part = nullptr, *exp_p = nullptr, *exp_part = nullptr;
    const int rc = Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &imp_g, &imp_l, &imp_p,
                                       &imp_part, &nexp, &exp_g, &exp_l, &exp_p, &exp_part);
    std::vector<int> part(x.size(), -1);
    if (rc == ZOLTAN_OK || rc == ZOLTAN_WARN) {
        // RETURN_LISTS = PARTS: the export lists hold every local object with its new part
        for (int k = 0; k < nexp; ++k)
            part[exp_l[k]] = exp_part[k];
    }
    Zoltan_LB_Free_Part(&imp_g, &imp_l, &imp_p, &imp_part);
    Zoltan_LB_Free_Part(&exp_g, &exp_l, &exp_p, &exp_part);
    Zoltan_Destroy(&zz);
    // every process the same outcome: a process whose Zoltan failed must not leave the others
    // waiting in the next collective (spec D9), so the smallest code (errors are negative) is
    // every process's
    check(static_cast<int>(comm.min(static_cast<double>(rc))), "Zoltan_LB_Partition");
    for (int p : part) {
        if (p < 0) throw std::runtime_error("Zoltan: a point was given no part");
    }
    return part;
}

std::vector<int32_t> rcb_group_owners(const MpiComm& comm, const Model& m, int parts) {
    std::vector<Vec2> centre;
    std::vector<double> weight;
    node_group_points(m, centre, weight);
    return rcb_group_owners(comm, centre, weight, parts);
}

std::vector<int32_t> rcb_group_owners(const MpiComm& comm, std::span<const Vec2> centre,
                                      std::span<const double> weight, int parts) {
    if (weight.size() != centre.size()) {
        throw std::invalid_argument("rcb_group_owners: centre and weight differ in length");
    }
    const size_t groups = centre.size();
    const int P = comm.size(), r = comm.rank();
    const size_t nparts = static_cast<size_t>(parts > 0 ? parts : P);
    if (groups < nparts) {
        // fewer node groups than parts (a model of < 64 P nodes): some process would hand
        // Zoltan no point, which its RCB refuses (ZOLTAN_FATAL); group g goes to part g, the
        // other parts own nothing (the same on every process count asked for these parts)
        std::vector<int32_t> owner(groups);
        std::iota(owner.begin(), owner.end(), 0);
        return owner;
    }
    const size_t b = groups * static_cast<size_t>(r) / static_cast<size_t>(P);
    const size_t e = groups * static_cast<size_t>(r + 1) / static_cast<size_t>(P);
    std::vector<uint64_t> gid(e - b);
    for (size_t g = b; g < e; ++g)
        gid[g - b] = g;
    const std::vector<int> part = rcb_parts(comm, centre.subspan(b, e - b),
                                            weight.subspan(b, e - b), gid, parts > 0 ? parts : P);
    std::vector<char> mine(part.size() * sizeof(int32_t)), all;
    for (size_t k = 0; k < part.size(); ++k) {
        const int32_t p = part[k];
        std::memcpy(mine.data() + k * sizeof p, &p, sizeof p);
    }
    comm.allgather_bytes(mine, all);  // in rank order: the groups in order
    std::vector<int32_t> owner(groups);
    if (all.size() != groups * sizeof(int32_t)) {
        throw std::runtime_error("rcb_group_owners: the gathered parts do not cover the groups");
    }
    std::memcpy(owner.data(), all.data(), all.size());
    // Zoltan numbers the parts of the same cuts differently on different process counts (one
    // process asked for P parts by `fdem decompose`, or P processes): number them in the order
    // of their first group, so that both give the same owners
    std::vector<int32_t> label(static_cast<size_t>(parts > 0 ? parts : P), -1);
    int32_t next = 0;
    for (int32_t& o : owner) {
        int32_t& l = label[static_cast<size_t>(o)];
        if (l < 0) l = next++;
        o = l;
    }
    return owner;
}

}  // namespace fdem
