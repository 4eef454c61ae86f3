// KioskApp's side of the operator mode (operator_mode.h): its controls' actions.
#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

void KioskApp::activate_operator(const Control& c) {
    switch (c.id) {  // `c` lives in controls_: read before relayout()
        case ControlId::OperatorKey: operator_.key(c.group); break;
        case ControlId::OperatorRestart:
            operator_.close();
            exit_requested_ = true;  // the service manager starts a fresh kiosk (Restart=always)
            break;
        case ControlId::OperatorClose: operator_.close(); break;
        default: break;
    }
    relayout();
}

}  // namespace body::kiosk
