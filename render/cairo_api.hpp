#pragma once
/// The cairo functions campo's figures call, loaded from libcairo on first use
/// rather than linked: cairo brings fontconfig, FreeType, pixman and the X11
/// client libraries (eleven libraries) into every process that links it, which
/// doubled the start of `campo --help` and of every run of a Slurm array; only
/// drawing a figure needs it. Call cairo as cairo().name(...) for cairo_name(...).
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

namespace campo {

/// The cairo functions campo calls, by their names without "cairo_"; the
/// headers' declarations give their types.
#define CAMPO_CAIRO_FUNCTIONS(X) \
  X(arc) \
  X(clip) \
  X(close_path) \
  X(create) \
  X(destroy) \
  X(fill) \
  X(get_source) \
  X(image_surface_create) \
  X(image_surface_get_data) \
  X(image_surface_get_stride) \
  X(line_to) \
  X(move_to) \
  X(new_path) \
  X(paint) \
  X(pattern_set_extend) \
  X(pattern_set_filter) \
  X(pdf_surface_create_for_stream) \
  X(pdf_surface_set_metadata) \
  X(recording_surface_create) \
  X(rectangle) \
  X(restore) \
  X(rotate) \
  X(save) \
  X(scale) \
  X(select_font_face) \
  X(set_dash) \
  X(set_font_size) \
  X(set_line_cap) \
  X(set_line_join) \
  X(set_line_width) \
  X(set_source_rgb) \
  X(set_source_surface) \
  X(show_text) \
  X(status_to_string) \
  X(stroke) \
  X(surface_destroy) \
  X(surface_finish) \
  X(surface_flush) \
  X(surface_mark_dirty) \
  X(surface_status) \
  X(svg_surface_create_for_stream) \
  X(svg_surface_restrict_to_version) \
  X(text_extents) \
  X(text_path) \
  X(translate)

struct CairoApi {
#define CAMPO_CAIRO_MEMBER(name) decltype(&cairo_##name) name = nullptr;
  CAMPO_CAIRO_FUNCTIONS(CAMPO_CAIRO_MEMBER)
#undef CAMPO_CAIRO_MEMBER
};

/// The functions; loads libcairo the first time (thread-safe). Throws
/// std::runtime_error naming the library or the function it lacks.
const CairoApi& cairo();

}  // namespace campo
