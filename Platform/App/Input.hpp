// The demo's own key and action types: the platform layer translates its key codes into these.
#pragma once

#include <array>

namespace sr::app {

// Keys the demo reacts to; the platform maps its virtual-key codes here (Unknown otherwise).
// Count is not a key: it sizes per-key tables.
enum class Key {
    Unknown,
    Escape,
    W, A, S, D, Q, E,          // fly: forward / strafe left / back / strafe right / down / up
    Up, Down, Left, Right,     // turn
    Shift,                     // held: move faster
    C, M, T, P, N, L, O, H, Z, R, V, G, U, K, I, // toggles, reset, camera and variant (see actionForKey)
    Space, Comma, Period,      // animation: play / pause, step back, step forward
    F1, F12,
    Count
};

inline constexpr int kKeyCount = int(Key::Count);

// What a key PRESS does (a held key's effect - flying, turning - is DemoController::update's).
enum class Action {
    None,
    Quit,
    CycleCull,        // none -> cull CW -> cull CCW -> none
    CycleShading,     // unlit -> flat -> gouraud -> phong (-> pbr in a glTF scene)
    ToggleColour,     // linear light <-> display values (ColorMode)
    CycleFilter,      // nearest -> bilinear -> trilinear
    CyclePerspective, // exact <-> affine
    CycleAntialiasing, // off -> MSAA 2 -> 4 -> 8 -> SSAA 4 -> 16 -> off
    ToggleWireframe,
    ToggleOutline,    // the selection outline of the object at the screen centre
    ToggleShadows,    // shadow maps on / off
    ToggleDepthView,  // show the depth buffer as grey
    ResetView,        // back to the starting camera
    CycleCamera,      // the flags' view -> the file's camera 0 -> 1 -> ... -> the flags' view
    ToggleHelp,
    Screenshot,
    TogglePlay,       // a glTF file's animation: play <-> pause
    StepBack,         // pause, one step (1/30 s) back
    StepForward,      // pause, one step forward
    ToggleAutoQuality, // --quality auto: keep the budget <-> hold the current setting
    CycleVariant,     // glTF KHR_materials_variants: the file's materials -> variant 0 -> 1 -> ... (the platform's: it reloads)
    ToggleSkyLight    // a pbr scene in front of a sky: lit by the sky too <-> by its lights alone
};

constexpr Action actionForKey(Key key) {
    switch (key) {
    case Key::Escape: return Action::Quit;
    case Key::C: return Action::CycleCull;
    case Key::M: return Action::CycleShading;
    case Key::T: return Action::CycleFilter;
    case Key::P: return Action::CyclePerspective;
    case Key::N: return Action::CycleAntialiasing;
    case Key::L: return Action::ToggleWireframe;
    case Key::O: return Action::ToggleOutline;
    case Key::H: return Action::ToggleShadows;
    case Key::G: return Action::ToggleColour;
    case Key::Z: return Action::ToggleDepthView;
    case Key::R: return Action::ResetView;
    case Key::V: return Action::CycleCamera;
    case Key::F1: return Action::ToggleHelp;
    case Key::F12: return Action::Screenshot;
    case Key::Space: return Action::TogglePlay;
    case Key::Comma: return Action::StepBack;
    case Key::Period: return Action::StepForward;
    case Key::U: return Action::ToggleAutoQuality;
    case Key::K: return Action::CycleVariant;
    case Key::I: return Action::ToggleSkyLight;
    default: break;
    }
    return Action::None;
}

// The key list of the help overlay and of --help: {keys, what they do}.
struct KeyHelp {
    const char* keys;
    const char* what;
};

inline constexpr std::array<KeyHelp, 25> kKeyHelp{{
    {"W / S", "fly forward / back"},
    {"A / D", "strafe left / right"},
    {"Q / E", "fly down / up"},
    {"Arrows, left-drag", "turn (look around)"},
    {"Shift", "hold to move 4x faster"},
    {"R", "reset the view"},
    {"V", "next camera of the model (glTF), then back to the start"},
    {"K", "next material variant of the model (glTF), then its own materials"},
    {"C", "cull mode: none -> CW -> CCW"},
    {"M", "shading: unlit -> flat -> gouraud -> phong (-> pbr, glTF)"},
    {"G", "colour: linear light <-> display values"},
    {"T", "texture filter: nearest -> bilinear -> trilinear"},
    {"P", "perspective: exact <-> affine"},
    {"N", "anti-aliasing: off -> MSAA 2, 4, 8 -> SSAA 4, 16"},
    {"L", "wireframe overlay on / off"},
    {"O", "outline of the object at the screen centre on / off"},
    {"H", "shadows on / off"},
    {"I", "light from the sky (glTF, pbr) on / off"},
    {"Z", "depth view (near = white) on / off"},
    {"Space", "animation (glTF): play / pause"},
    {", / .", "animation: pause and step 1/30 s back / forward"},
    {"U", "--quality auto: follow the budget <-> hold the setting"},
    {"F1", "this help on / off"},
    {"F12", "save a screenshot (PNG, current folder)"},
    {"Esc", "quit"},
}};

} // namespace sr::app
