// The halo exchange of a distributed run over MPI (docs/theory.md section 13): each process sends
// its owned points' values to the processes that hold them as ghosts and receives its ghosts'
// values from their owners, with one message per neighbouring process and field. The lists are
// agreed once, when the run starts: each process asks every owner for its ghosts by global id.
#pragma once
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "solver/ghost_exchange.hpp"
#include "solver/local_points.hpp"

namespace mppm::solver {

class HaloExchange final : public GhostExchange {
 public:
  // Collective: every process of MPI_COMM_WORLD calls it with its local points and the part (the
  // process) of every point.
  HaloExchange(const LocalPoints& local, std::span<const std::int32_t> part_of);

  void update_ghosts(std::vector<double>& values, int components) const override;
  std::vector<PointNote> notify_owners(std::span<const PointNote> about_ghosts) const override;
  void begin_update(std::vector<double>& values, int components) const override;
  void finish_updates() const override;
  void advance_transfers() const override;

  // The processes this one exchanges with, and the points it sends and receives per exchange.
  std::size_t neighbours() const { return links_.size(); }
  std::size_t points_sent() const;
  std::size_t points_received() const;

  // What the exchanges since construction cost this process: their number, the values (doubles)
  // and messages it sent, and the wall time inside update_ghosts (seconds), of it packing the send
  // buffers, waiting for the messages and unpacking the received ones.
  struct Traffic {
    std::int64_t exchanges = 0, values_sent = 0, messages_sent = 0;
    double seconds = 0.0, pack_seconds = 0.0, wait_seconds = 0.0, unpack_seconds = 0.0;
  };
  const Traffic& traffic() const { return traffic_; }

 private:
  struct Link {
    int rank = 0;
    std::vector<std::size_t> send;     // local indices of owned points, in the receiver's order
    std::vector<std::size_t> receive;  // local indices of ghosts (ascending global id)
  };
  std::vector<Link> links_;
  std::size_t owned_ = 0;
  // Per ghost (local index - owned_): its link and its place in the link's receive list.
  std::vector<std::pair<std::size_t, std::size_t>> ghost_slot_;
  // A begun field: where its ghosts' values go, and its buffers per link (kept from one exchange to
  // the next: no allocation in the time loop once warm).
  struct Field {
    std::vector<double>* values = nullptr;
    std::size_t components = 0;
    std::vector<std::vector<double>> send, receive;
  };
  mutable std::vector<Field> fields_;  // slots; the first `begun_` are in flight
  mutable std::size_t begun_ = 0;
  mutable std::vector<MPI_Request> requests_;
  mutable Traffic traffic_;
};

}  // namespace mppm::solver
