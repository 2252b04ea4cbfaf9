// Lines of text over the scene, in the window's top left corner: the viewer's scene, solver,
// simulated time and solve time, so that a screenshot says what it shows. drawstuff has no text,
// so the glyphs come from an X core font turned into GL display lists (glXUseXFont); X.org's
// servers, Xvfb included, have "fixed" built in.
#pragma once

#include <GL/gl.h>

#include <string>
#include <vector>

namespace ode_bpp::viewer {

class TextOverlay {
public:
    TextOverlay() = default;
    ~TextOverlay();
    TextOverlay(const TextOverlay&) = delete;
    TextOverlay& operator=(const TextOverlay&) = delete;

    /// Builds the glyphs on the GL context current on this thread (drawstuff's, from its start
    /// callback on). False, with no text drawn later, if no font could be loaded.
    bool load();

    /// Draws the lines, white on a translucent dark panel, over whatever the frame holds; leaves
    /// drawstuff's GL state (matrices, enables, colour) as it found it.
    void draw(const std::vector<std::string>& lines) const;

private:
    GLuint first_list_ = 0;   ///< display list of character kFirstChar
    GLsizei list_count_ = 0;
    int ascent_ = 0, descent_ = 0, char_width_ = 0;
};

}  // namespace ode_bpp::viewer
