// examples/filament/x_display.h — the X display Filament's OpenGL backend (GLX) needs, opened
// before Filament tries: without one Filament aborts. Xlib's macros (Status, None, Bool) clash
// with footprint's and Filament's names, so only x_display.cpp includes it.
#pragma once

#include <string>

namespace footprint::filament_example {

// Opens the default display ($DISPLAY); null and the reason when it cannot.
void* open_x_display(std::string* why);
void close_x_display(void* display);

}  // namespace footprint::filament_example
