#include "parallel/mesh_broadcast.hpp"

#include <exception>
#include <stdexcept>
#include <string_view>

#include "io/mesh_bytes.hpp"

namespace fdem {

MeshReader broadcast_mesh_reader(const Comm& comm) {
    return [&comm](const std::string& path, Real mesh_size, int order,
                   const MeshLimits& limits) -> MeshData {
        // the first byte of what process 0 sends: a mesh, or the error it met (encode_error)
        constexpr char kMesh = 'M', kError = 'E';
        std::string bytes;
        std::exception_ptr failure;
        if (comm.rank() == 0) {
            try {
                const MeshData mesh = read_mesh(path, mesh_size, order, limits);
                bytes.assign(1, kMesh);
                bytes += mesh_to_bytes(mesh);
            } catch (const std::exception& e) {
                failure = std::current_exception();
                bytes = kError + encode_error(e);
            }
        }
        comm.broadcast(bytes, 0);
        if (failure) std::rethrow_exception(failure);  // process 0: its own exception
        if (bytes.empty()) throw std::runtime_error("mesh broadcast: nothing received");
        if (bytes[0] == kError) throw_decoded_error(bytes.substr(1));
        return mesh_from_bytes(std::string_view(bytes).substr(1));
    };
}

}  // namespace fdem
