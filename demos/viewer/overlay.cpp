#include "overlay.h"

#include <GL/glx.h>
#include <X11/Xlib.h>

#include <algorithm>

namespace ode_bpp::viewer {
namespace {

constexpr int kFirstChar = 32, kLastChar = 126;  // printable ASCII
constexpr int kMargin = 8;                       // panel to window edge and text to panel edge [px]
constexpr int kLineGap = 2;                      // between lines [px]
constexpr float kPanelAlpha = 0.65f;
// a larger font where the X server has one; "fixed" is built into every X server
const char* const kFonts[] = {"-misc-fixed-bold-r-normal--18-*-*-*-*-*-iso8859-1", "9x15bold", "9x15", "fixed"};

}  // namespace

TextOverlay::~TextOverlay() {
    if (list_count_ > 0 && glXGetCurrentContext() != nullptr) glDeleteLists(first_list_, list_count_);
}

bool TextOverlay::load() {
    Display* display = glXGetCurrentDisplay();
    if (display == nullptr || list_count_ > 0) return list_count_ > 0;
    XFontStruct* font = nullptr;
    for (const char* name : kFonts)
        if ((font = XLoadQueryFont(display, name)) != nullptr) break;
    if (font == nullptr) return false;
    const GLsizei count = kLastChar - kFirstChar + 1;
    const GLuint base = glGenLists(count);
    if (base != 0) {
        glXUseXFont(font->fid, kFirstChar, count, static_cast<int>(base));
        first_list_ = base;
        list_count_ = count;
        ascent_ = font->ascent;
        descent_ = font->descent;
        char_width_ = font->max_bounds.width;
    }
    XFreeFont(display, font);
    return list_count_ > 0;
}

void TextOverlay::draw(const std::vector<std::string>& lines) const {
    if (list_count_ == 0 || lines.empty()) return;
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    const int height = viewport[3];
    size_t longest = 0;
    for (const std::string& line : lines) longest = std::max(longest, line.size());
    const int line_height = ascent_ + descent_ + kLineGap;
    const int panel_w = static_cast<int>(longest) * char_width_ + 2 * kMargin;
    const int panel_h = static_cast<int>(lines.size()) * line_height + 2 * kMargin;

    glPushAttrib(GL_ENABLE_BIT | GL_CURRENT_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glPushMatrix();
    glLoadIdentity();
    glOrtho(0, viewport[2], 0, height, -1, 1);  // window pixels, y up
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity();
    glDisable(GL_LIGHTING);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_FOG);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

    const int left = kMargin, top = height - kMargin;
    glColor4f(0.0f, 0.0f, 0.0f, kPanelAlpha);
    glRecti(left, top - panel_h, left + panel_w, top);
    glColor4f(1.0f, 1.0f, 1.0f, 1.0f);
    // one raster position per character cell (the fonts are fixed-width): Mesa's glyph of the
    // blank has no bitmap and does not advance the raster position
    for (size_t i = 0; i < lines.size(); ++i) {
        const int baseline = top - kMargin - static_cast<int>(i) * line_height - ascent_;
        for (size_t k = 0; k < lines[i].size(); ++k) {
            const int c = static_cast<unsigned char>(lines[i][k]);
            if (c == ' ') continue;
            glRasterPos2i(left + kMargin + static_cast<int>(k) * char_width_, baseline);
            glCallList(first_list_ + static_cast<GLuint>((c >= kFirstChar && c <= kLastChar ? c : '?') - kFirstChar));
        }
    }

    glPopMatrix();
    glMatrixMode(GL_PROJECTION);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
    glPopAttrib();
}

}  // namespace ode_bpp::viewer
