#pragma once
// The pixel orders a FrustumBand is compiled for. Each kinetic/frustum_band_*.cpp defines one
// part of the band's member functions and instantiates exactly those for each sort, through
// KINRAY_FOR_EACH_BAND_SORT, so that every member is instantiated once in the program.
#include "kinetic/grid/pixel_depth_order.h"
#include "kinetic/sort/kinetic_heap.h"
#include "kinetic/sort/kinetic_sorted_list.h"
#include "kinetic/sort/kinetic_tournament.h"

/// X(Sort) for each pixel order a band can use (FrustumGrid picks one by DepthSortKind).
#define KINRAY_FOR_EACH_BAND_SORT(X)       \
  X(KineticSortedList<PixelDepthKeys>)     \
  X(KineticTournament<PixelDepthKeys>)     \
  X(KineticHeap<PixelDepthKeys>)
