#pragma once
// The viewer's colour legend: a vertical bar with the transfer function's colours, the array's
// name above it, the range's ends and nicely rounded ticks beside it (overlay/ticks.h, as the
// CPU pictures' legend), drawn on ImGui's background draw list at the window's right edge.
// Being ImGui, it is in the window and in --panel-in-screenshot pictures, never in a plain
// headless screenshot (those are compared with the CPU renderer pixel for pixel).

#include <project/transfer_function.h>

#include <string>

namespace tr::viewer {

// Draws the legend into the current ImGui frame (between NewFrame and Render). `decades`: the
// transfer function takes log10 of the values, so the labels are 10^s and the ticks the
// powers of ten.
void draw_legend_overlay(const TransferFunction& tf, const std::string& title,
                         bool decades = false);

}  // namespace tr::viewer
