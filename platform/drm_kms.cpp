// The kernel call table over libdrm (contract in drm_kms.h).
#include "platform/drm_kms.h"

#include <poll.h>

#include <cstring>
#include <string>

namespace body::platform {
namespace {

int poll_readable(int fd, int timeout_ms) {
    pollfd p{fd, POLLIN, 0};
    return ::poll(&p, 1, timeout_ms);
}

uint32_t property_id(int fd, uint32_t object, uint32_t type, const char* name) {
    drmModeObjectProperties* props = drmModeObjectGetProperties(fd, object, type);
    if (!props) return 0;
    uint32_t found = 0;
    for (uint32_t i = 0; i < props->count_props && !found; ++i) {
        drmModePropertyRes* p = drmModeGetProperty(fd, props->props[i]);
        if (!p) continue;
        if (std::strcmp(p->name, name) == 0) found = p->prop_id;
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return found;
}

// The value of `object`'s property `name`, or `otherwise`.
uint64_t property_value(int fd, uint32_t object, uint32_t type, const char* name, uint64_t otherwise) {
    drmModeObjectProperties* props = drmModeObjectGetProperties(fd, object, type);
    if (!props) return otherwise;
    uint64_t value = otherwise;
    for (uint32_t i = 0; i < props->count_props; ++i) {
        drmModePropertyRes* p = drmModeGetProperty(fd, props->props[i]);
        if (!p) continue;
        if (std::strcmp(p->name, name) == 0) value = props->prop_values[i];
        drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
    return value;
}

// kmscube's get_plane_id: the plane whose possible_crtcs has the CRTC's index
// bit and whose "type" is primary.
uint32_t primary_plane(int fd, uint32_t crtc_id) {
    drmModeRes* res = drmModeGetResources(fd);
    if (!res) return 0;
    int index = -1;
    for (int i = 0; i < res->count_crtcs; ++i)
        if (res->crtcs[i] == crtc_id) index = i;
    drmModeFreeResources(res);
    drmModePlaneRes* planes = drmModeGetPlaneResources(fd);
    if (!planes || index < 0) {
        if (planes) drmModeFreePlaneResources(planes);
        return 0;
    }
    uint32_t found = 0;
    for (uint32_t i = 0; i < planes->count_planes && !found; ++i) {
        drmModePlane* plane = drmModeGetPlane(fd, planes->planes[i]);
        if (!plane) continue;
        if ((plane->possible_crtcs & (1u << index)) &&
            property_value(fd, plane->plane_id, DRM_MODE_OBJECT_PLANE, "type", ~0ull) == DRM_PLANE_TYPE_PRIMARY)
            found = plane->plane_id;
        drmModeFreePlane(plane);
    }
    drmModeFreePlaneResources(planes);
    return found;
}

int create_blob(int fd, const void* data, size_t size, uint32_t* blob_id) {
    return drmModeCreatePropertyBlob(fd, data, size, blob_id);
}

int atomic_commit(int fd, const DrmAtomicProp* props, size_t count, uint32_t flags, void* user_data) {
    drmModeAtomicReq* req = drmModeAtomicAlloc();
    if (!req) return -1;
    int rc = 0;
    for (size_t i = 0; i < count && rc >= 0; ++i)
        rc = drmModeAtomicAddProperty(req, props[i].object, props[i].property, props[i].value);
    if (rc >= 0) rc = drmModeAtomicCommit(fd, req, flags, user_data);
    drmModeAtomicFree(req);
    return rc < 0 ? rc : 0;
}

std::string connector_name(const drmModeConnector* c) {
    const char* type = drmModeGetConnectorTypeName(c->connector_type);
    return std::string(type ? type : "Unknown") + "-" + std::to_string(c->connector_type_id);
}

DrmProbedConnector describe(int fd, const drmModeRes* res, const drmModeConnector* c) {
    DrmProbedConnector out;
    DrmConnector& d = out.desc;
    d.id = c->connector_id;
    d.name = connector_name(c);
    d.connected = c->connection == DRM_MODE_CONNECTED;
    out.mm_width = c->mmWidth;
    for (int m = 0; m < c->count_modes; ++m) {
        out.modes.push_back(c->modes[m]);
        d.modes.push_back({c->modes[m].hdisplay, c->modes[m].vdisplay, static_cast<int>(c->modes[m].vrefresh),
                           (c->modes[m].type & DRM_MODE_TYPE_PREFERRED) != 0});
    }
    if (c->encoder_id) {
        if (drmModeEncoder* e = drmModeGetEncoder(fd, c->encoder_id)) {
            d.current_crtc = e->crtc_id;
            drmModeFreeEncoder(e);
        }
    }
    for (int e = 0; e < c->count_encoders; ++e) {
        drmModeEncoder* enc = drmModeGetEncoder(fd, c->encoders[e]);
        if (!enc) continue;
        for (int k = 0; k < res->count_crtcs; ++k)
            if (enc->possible_crtcs & (1u << k)) d.possible_crtcs.push_back(res->crtcs[k]);
        drmModeFreeEncoder(enc);
    }
    return out;
}

// drmModeGetConnector asks the driver to probe again (a hotplug's new modes).
std::vector<DrmProbedConnector> probe(int fd) {
    std::vector<DrmProbedConnector> out;
    drmModeRes* res = drmModeGetResources(fd);
    if (!res) return out;
    for (int i = 0; i < res->count_connectors; ++i) {
        drmModeConnector* c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c) continue;
        out.push_back(describe(fd, res, c));
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return out;
}

const DrmOps kRealOps = {drmModeGetCrtc,  drmModeFreeCrtc, drmModeSetCrtc, poll_readable, drmHandleEvent,
                         drmSetClientCap, property_id,     primary_plane,  create_blob,   drmModeDestroyPropertyBlob,
                         atomic_commit,   drmModePageFlip, drmSetMaster,   probe};

}  // namespace

const DrmOps& real_drm_ops() { return kRealOps; }

}  // namespace body::platform
