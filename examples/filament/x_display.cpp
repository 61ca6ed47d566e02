// examples/filament/x_display.cpp — x_display.h.
#include "x_display.h"

#include <X11/Xlib.h>

#include <cstdlib>

namespace footprint::filament_example {

void* open_x_display(std::string* why) {
    Display* display = XOpenDisplay(nullptr);
    if (!display) {
        const char* name = std::getenv("DISPLAY");
        *why = std::string("cannot open the X display '") + (name ? name : "") +
               "' that Filament's OpenGL backend needs (run under xvfb-run -a)";
    }
    return display;
}

void close_x_display(void* display) {
    if (display) XCloseDisplay(static_cast<Display*>(display));
}

}  // namespace footprint::filament_example
