#pragma once
// Test support: a figure's PDF and SVG read back by programs other than the
// one that wrote them. poppler's pdftotext finds the texts in the PDF as text
// and pdftoppm renders it; xmllint checks the SVG is well-formed XML; librsvg's
// rsvg-convert renders it. Both renderings must match the PNG raster of the
// same drawing (tools/setup.sh installs the three programs).
#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "render/figure_canvas.hpp"

namespace campo::figure::test {

// Standard output of `command` (run by the shell) and its exit status.
struct CommandOutput {
  std::string text;
  int status = -1;
};

inline CommandOutput run_command(const std::string& command) {
  CommandOutput out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.text.append(buffer.data(), n);
  out.status = pclose(pipe);
  return out;
}

inline std::string without_spaces(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  }
  return out;
}

// Mean absolute difference per channel between two BGR images of one size, 0-255.
inline double mean_abs_difference(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return 255.0;
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  const cv::Scalar m = cv::mean(diff);
  return (m[0] + m[1] + m[2]) / 3.0;
}

// A figure's vector outputs checked against its raster: the PDF holds `texts`
// as text, the SVG is well-formed XML sized 0.75 pt per pixel, each renders
// within `max_mean_difference` (0-255 per channel, on average) of raster(),
// and encoding twice gives the same bytes.
inline void expect_vector_outputs(const Canvas& canvas, const std::vector<std::string>& texts,
                                  double max_mean_difference = 6.0) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("campo_vector_" + std::to_string(::getpid()) + "_" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto written = canvas.write(dir / "figure", {FigureFormat::png, FigureFormat::pdf, FigureFormat::svg});
  ASSERT_EQ(written.size(), 3u);
  const cv::Mat raster = canvas.raster();
  const cv::Mat png = cv::imread((dir / "figure.png").string(), cv::IMREAD_COLOR);
  EXPECT_EQ(mean_abs_difference(png, raster), 0.0) << "the PNG file is the raster";

  const std::string pdf = canvas.encode(FigureFormat::pdf);
  EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
  EXPECT_EQ(pdf, canvas.encode(FigureFormat::pdf)) << "same drawing, same PDF bytes";
  const CommandOutput pdf_text = run_command("pdftotext -q '" + (dir / "figure.pdf").string() + "' -");
  EXPECT_EQ(pdf_text.status, 0);
  const std::string found = without_spaces(pdf_text.text);
  for (const auto& t : texts) EXPECT_NE(found.find(without_spaces(t)), std::string::npos) << "PDF text lacks: " << t;
  EXPECT_EQ(run_command("pdftoppm -q -r 96 -png -singlefile '" + (dir / "figure.pdf").string() + "' '" +
                        (dir / "from_pdf").string() + "'").status, 0);
  const cv::Mat from_pdf = cv::imread((dir / "from_pdf.png").string(), cv::IMREAD_COLOR);
  EXPECT_LE(mean_abs_difference(from_pdf, raster), max_mean_difference) << "PDF rendered by poppler vs PNG";

  const std::string svg = canvas.encode(FigureFormat::svg);
  EXPECT_EQ(svg, canvas.encode(FigureFormat::svg)) << "same drawing, same SVG bytes";
  EXPECT_EQ(run_command("xmllint --noout '" + (dir / "figure.svg").string() + "' 2>&1").status, 0);
  // 0.75 pt per pixel; a width that is a multiple of 4 pixels is a whole number of points.
  if (canvas.size().width % 4 == 0) {
    const std::string width = "width=\"" + std::to_string(canvas.size().width * 3 / 4) + "pt\"";
    EXPECT_NE(svg.find(width), std::string::npos) << svg.substr(0, 300);
  }
  EXPECT_EQ(run_command("rsvg-convert -w " + std::to_string(canvas.size().width) + " -h " +
                        std::to_string(canvas.size().height) + " -b white -o '" + (dir / "from_svg.png").string() +
                        "' '" + (dir / "figure.svg").string() + "'").status, 0);
  const cv::Mat from_svg = cv::imread((dir / "from_svg.png").string(), cv::IMREAD_COLOR);
  EXPECT_LE(mean_abs_difference(from_svg, raster), max_mean_difference) << "SVG rendered by librsvg vs PNG";
  fs::remove_all(dir);
}

}  // namespace campo::figure::test
