// Gesture recognition over touch and mouse events (contract in gestures.h).
#include "kiosk/app/gestures.h"

#include <cmath>

namespace body::kiosk {

namespace {

float distance(float ax, float ay, float bx, float by) { return std::hypot(ax - bx, ay - by); }

}  // namespace

void GestureRecognizer::reset() {
    touches_.clear();
    moved_ = multi_ = pending_ = false;
    mouse_down_ = mouse_dragging_ = false;
}

void GestureRecognizer::anchor() {
    if (touches_.size() < 2) return;
    auto a = touches_.begin();
    auto b = std::next(a);
    anchor_cx_ = (a->second.x + b->second.x) * 0.5f;
    anchor_cy_ = (a->second.y + b->second.y) * 0.5f;
    anchor_d_ = distance(a->second.x, a->second.y, b->second.x, b->second.y);
}

void GestureRecognizer::flush(std::vector<Gesture>& out) {
    if (!pending_) return;
    pending_ = false;
    if (touches_.size() < 2) return;
    auto a = touches_.begin();
    auto b = std::next(a);
    const float cx = (a->second.x + b->second.x) * 0.5f, cy = (a->second.y + b->second.y) * 0.5f;
    const float d = distance(a->second.x, a->second.y, b->second.x, b->second.y);
    if (anchor_d_ > 1.0f && d > 1.0f && d != anchor_d_) {
        Gesture g{GestureKind::Zoom, pending_time_, cx, cy};
        g.factor = d / anchor_d_;
        out.push_back(g);
    }
    if (cx != anchor_cx_ || cy != anchor_cy_) {
        out.push_back(Gesture{GestureKind::Pan, pending_time_, cx, cy, cx - anchor_cx_, cy - anchor_cy_});
    }
    anchor();
}

void GestureRecognizer::feed(const InputEvent& e, std::vector<Gesture>& out) {
    if (pending_ &&
        (e.time != pending_time_ || e.type == InputEvent::Type::TouchDown || e.type == InputEvent::Type::TouchUp)) {
        flush(out);
    }
    switch (e.type) {
        case InputEvent::Type::TouchDown:
        case InputEvent::Type::TouchMove:
        case InputEvent::Type::TouchUp: touch(e, out); break;
        case InputEvent::Type::Key:
        case InputEvent::Type::Text:
        case InputEvent::Type::Quit: break;
        default: mouse(e, out); break;
    }
}

void GestureRecognizer::touch(const InputEvent& e, std::vector<Gesture>& out) {
    if (e.type == InputEvent::Type::TouchDown) {
        if (touches_.empty()) moved_ = multi_ = false;
        touches_[e.id] = Touch{e.x, e.y, e.x, e.y, e.time};
        if (touches_.size() >= 2) multi_ = true;
        anchor();
        out.push_back(Gesture{GestureKind::Begin, e.time, e.x, e.y});
        return;
    }
    auto it = touches_.find(e.id);
    if (it == touches_.end()) return;  // a contact we never saw go down
    if (e.type == InputEvent::Type::TouchMove) {
        if (touches_.size() == 1) {
            Touch& t = it->second;
            if (!moved_ && distance(e.x, e.y, t.start_x, t.start_y) < settings_.slop_px) return;
            const float dx = moved_ ? e.x - t.x : e.x - t.start_x;
            const float dy = moved_ ? e.y - t.y : e.y - t.start_y;
            moved_ = true;
            t.x = e.x;
            t.y = e.y;
            if (!multi_) out.push_back(Gesture{GestureKind::Orbit, e.time, e.x, e.y, dx, dy});
            return;
        }
        // Two (or more) fingers: the first two define pinch and pan, reported per frame.
        it->second.x = e.x;
        it->second.y = e.y;
        moved_ = true;
        pending_ = true;
        pending_time_ = e.time;
        return;
    }
    // TouchUp
    const Touch t = it->second;
    touches_.erase(it);
    if (!touches_.empty()) {
        // Fingers remain: re-anchor them so a later one-finger move does not jump.
        for (auto& [id, other] : touches_) {
            other.start_x = other.x;
            other.start_y = other.y;
        }
        anchor();
        return;
    }
    const bool tap = !moved_ && !multi_ && e.time - t.start_time <= settings_.tap_seconds &&
                     distance(e.x, e.y, t.start_x, t.start_y) < settings_.slop_px;
    if (!tap) return;
    out.push_back(Gesture{GestureKind::Tap, e.time, t.start_x, t.start_y});
    if (e.time - last_tap_time_ <= settings_.double_tap_seconds &&
        distance(t.start_x, t.start_y, last_tap_x_, last_tap_y_) <= settings_.double_tap_px) {
        out.push_back(Gesture{GestureKind::DoubleTap, e.time, t.start_x, t.start_y});
        last_tap_time_ = -1e9;  // a third tap starts a new pair
    } else {
        last_tap_time_ = e.time;
        last_tap_x_ = t.start_x;
        last_tap_y_ = t.start_y;
    }
}

void GestureRecognizer::mouse(const InputEvent& e, std::vector<Gesture>& out) {
    if (e.type == InputEvent::Type::Scroll) {
        Gesture g{GestureKind::Zoom, e.time, e.x, e.y};
        g.factor = std::pow(settings_.wheel_zoom, e.dy);
        out.push_back(Gesture{GestureKind::Begin, e.time, e.x, e.y});
        out.push_back(g);
        return;
    }
    if (e.type == InputEvent::Type::MouseDown) {
        if (mouse_down_) return;  // one button at a time, like the thesis viewer
        mouse_down_ = true;
        mouse_button_ = e.button();
        mouse_shift_ = (e.modifiers & kModShift) != 0;
        mouse_dragging_ = false;
        mouse_x_ = mouse_start_x_ = e.x;
        mouse_y_ = mouse_start_y_ = e.y;
        out.push_back(Gesture{GestureKind::Begin, e.time, e.x, e.y});
        return;
    }
    if (!mouse_down_) return;
    if (e.type == InputEvent::Type::MouseMove) {
        if (!mouse_dragging_ && distance(e.x, e.y, mouse_start_x_, mouse_start_y_) < 3.0f) return;
        const float dx = e.x - mouse_x_, dy = e.y - mouse_y_;
        mouse_x_ = e.x;
        mouse_y_ = e.y;
        if (mouse_shift_) {
            if (mouse_button_ == MouseButton::Right) return;
            if (!mouse_dragging_) {
                Gesture g{GestureKind::DragStart, e.time, mouse_start_x_, mouse_start_y_};
                g.button = mouse_button_;
                out.push_back(g);
            }
            mouse_dragging_ = true;
            Gesture g{GestureKind::Drag, e.time, e.x, e.y, dx, dy};
            g.button = mouse_button_;
            out.push_back(g);
            return;
        }
        mouse_dragging_ = true;
        switch (mouse_button_) {
            case MouseButton::Left: out.push_back(Gesture{GestureKind::Orbit, e.time, e.x, e.y, dx, dy}); break;
            case MouseButton::Middle: out.push_back(Gesture{GestureKind::Pan, e.time, e.x, e.y, dx, dy}); break;
            case MouseButton::Right: {
                Gesture g{GestureKind::Zoom, e.time, e.x, e.y};
                g.factor = std::exp(-dy * settings_.right_drag_zoom_per_px);
                out.push_back(g);
                break;
            }
        }
        return;
    }
    if (e.type == InputEvent::Type::MouseUp && e.button() == mouse_button_) {
        mouse_down_ = false;
        if (mouse_dragging_ && mouse_shift_) {
            Gesture g{GestureKind::DragEnd, e.time, e.x, e.y};
            g.button = mouse_button_;
            out.push_back(g);
        } else if (!mouse_dragging_ && mouse_shift_ && mouse_button_ != MouseButton::Right) {
            Gesture g{GestureKind::Tap, e.time, mouse_start_x_, mouse_start_y_};
            g.button = mouse_button_;
            out.push_back(g);
        }
        mouse_dragging_ = false;
    }
}

}  // namespace body::kiosk
