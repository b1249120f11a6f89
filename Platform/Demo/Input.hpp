// The demo's own key and action types: the platform layer translates its key codes into these.
#pragma once

namespace sr::demo {

// Keys the demo reacts to; the platform maps its virtual-key codes here (Unknown otherwise).
enum class Key { Unknown, Escape };

enum class Action { None, Quit };

// What a key press does in the demo.
constexpr Action actionForKey(Key key) {
    switch (key) {
    case Key::Escape: return Action::Quit;
    case Key::Unknown: break;
    }
    return Action::None;
}

} // namespace sr::demo
