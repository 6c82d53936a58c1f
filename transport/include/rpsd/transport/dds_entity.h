// Small move-only owners of Cyclone DDS handles and QoS objects, and the one place where
// a DDS return code becomes an exception (at configure time) with dds_strretcode's text.
#pragma once

#include <dds/dds.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace rpsd::transport {

class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws DdsError("<what>: <dds_strretcode>") when rc is negative; returns rc otherwise.
// Not real-time safe.
dds_return_t dds_check(dds_return_t rc, const std::string& what);

// Owns one DDS entity (participant, topic, reader, writer, waitset, condition, domain).
class DdsEntity {
 public:
  DdsEntity() = default;
  // Takes ownership; throws DdsError naming `what` if the handle is an error code.
  DdsEntity(dds_entity_t handle, const std::string& what) : handle_(dds_check(handle, what)) {}
  ~DdsEntity() { reset(); }
  DdsEntity(DdsEntity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  DdsEntity& operator=(DdsEntity&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, 0);
    }
    return *this;
  }
  DdsEntity(const DdsEntity&) = delete;
  DdsEntity& operator=(const DdsEntity&) = delete;

  dds_entity_t get() const { return handle_; }
  explicit operator bool() const { return handle_ > 0; }
  void reset() {
    if (handle_ > 0) dds_delete(handle_);
    handle_ = 0;
  }

 private:
  dds_entity_t handle_ = 0;
};

// Owns a dds_qos_t.
class DdsQos {
 public:
  DdsQos() : qos_(dds_create_qos()) {}
  ~DdsQos() {
    if (qos_) dds_delete_qos(qos_);
  }
  DdsQos(DdsQos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {}
  DdsQos& operator=(DdsQos&& other) noexcept {
    std::swap(qos_, other.qos_);
    return *this;
  }
  DdsQos(const DdsQos&) = delete;
  DdsQos& operator=(const DdsQos&) = delete;
  dds_qos_t* get() const { return qos_; }

 private:
  dds_qos_t* qos_;
};

}  // namespace rpsd::transport
