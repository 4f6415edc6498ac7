#pragma once
/// PNG figures for reports (SPEC §9), drawn with OpenCV from recorded run data
/// alone: top-down map, side view, reconstructed height map, depth maps with
/// planner overlays, several runs overlaid and the map at several instants.
/// Anti-aliased, with title, axes in metres, scale bar and legend. Same inputs
/// => same pixels. One header per figure, all included here:
///   figure_style.hpp       RunView, FigureStyle, FigureLayout, shared colours
///   map_figure.hpp         draw_map, draw_overlay
///   height_map_figure.hpp  draw_height_map
///   sequence_figure.hpp    draw_sequence
///   side_view_figure.hpp   draw_side_view
///   depth_figure.hpp       draw_depth
/// Their private machinery: map_plot.hpp (map-like figures), figure_parts.hpp
/// (legend entries and checks several figures share), figure_canvas.hpp
/// (drawing primitives), figure_scene.hpp (the scene seen from above).
#include "render/depth_figure.hpp"
#include "render/figure_style.hpp"
#include "render/height_map_figure.hpp"
#include "render/map_figure.hpp"
#include "render/sequence_figure.hpp"
#include "render/side_view_figure.hpp"
