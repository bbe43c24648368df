#pragma once
// Counters of the kinetic grid (pbrt STAT_COUNTER style), summed over bands. Every event count
// is defined by the geometry and the motion alone (a boundary crossing a column centre, a vertex
// crossing a row plane, a swap in a pixel, ...), so it depends neither on how many frames are
// read out nor on how many bands the rows are split into.
#include <cstddef>
#include <cstdint>

namespace kinray {

struct GridEventCounts {
  uint64_t boundary = 0;     ///< a boundary crossed a column centre
  uint64_t vertex_row = 0;   ///< a vertex crossed a row plane (one per vertex and row)
  uint64_t orientation = 0;  ///< a triangle's plane swept through the eye (per band record set)
  uint64_t swap = 0;         ///< two triangles changed depth order in a pixel
  uint64_t flightplan = 0;   ///< a mesh reached a key (one per mesh and key)
  uint64_t insert = 0;       ///< a mesh appeared after the start
  uint64_t remove = 0;       ///< a mesh disappeared ("delete" in the stats)
  [[nodiscard]] uint64_t total() const {
    return boundary + vertex_row + orientation + swap + flightplan + insert + remove;
  }
  GridEventCounts& operator+=(const GridEventCounts& o) {
    boundary += o.boundary;
    vertex_row += o.vertex_row;
    orientation += o.orientation;
    swap += o.swap;
    flightplan += o.flightplan;
    insert += o.insert;
    remove += o.remove;
    return *this;
  }
};

struct GridStats {
  GridEventCounts events;
  uint64_t events_external = 0;  ///< events that changed some pixel's front triangle
  uint64_t events_internal = 0;  ///< the others
  uint64_t spurious = 0;         ///< certificate failures that were rounding, not changes
  uint64_t renewals = 0;         ///< depth certificates renewed at a flightplan update
  uint64_t coverage_changes = 0; ///< triangle inserted into / erased from a pixel's order
  uint64_t records_born = 0, records_died = 0, reties = 0;
  uint64_t row_rebuilds = 0;       ///< records rebuilt from scratch (orientation, degenerate)
  uint64_t degenerate_rebuilds = 0;///< of which: inconsistent signs at one instant
  uint64_t certificates_computed = 0;  ///< every certificate (re)computation, depth included
  uint64_t certificates_live = 0;      ///< now, summed over bands
  uint64_t certificates_live_max = 0;  ///< sum over bands of each band's maximum
  uint64_t records = 0;                ///< live (triangle, row) records
  uint64_t pixel_entries = 0;          ///< triangles held in the per-pixel orders
  uint64_t triangles_present = 0;
  uint64_t meshes_culling = 0;    ///< present meshes with back-face culling (now)
  uint64_t triangles_culled = 0;  ///< of their triangles: facing away now, so without records
  size_t memory_bytes = 0;             ///< now
  size_t pixel_memory_bytes = 0;       ///< of which: the per-pixel orders (instances + entries)

  GridStats& operator+=(const GridStats& o) {
    events += o.events;
    events_external += o.events_external;
    events_internal += o.events_internal;
    spurious += o.spurious;
    renewals += o.renewals;
    coverage_changes += o.coverage_changes;
    records_born += o.records_born;
    records_died += o.records_died;
    reties += o.reties;
    row_rebuilds += o.row_rebuilds;
    degenerate_rebuilds += o.degenerate_rebuilds;
    certificates_computed += o.certificates_computed;
    certificates_live += o.certificates_live;
    certificates_live_max += o.certificates_live_max;
    records += o.records;
    pixel_entries += o.pixel_entries;
    triangles_present += o.triangles_present;
    meshes_culling += o.meshes_culling;
    triangles_culled += o.triangles_culled;
    memory_bytes += o.memory_bytes;
    pixel_memory_bytes += o.pixel_memory_bytes;
    return *this;
  }
};

}  // namespace kinray
