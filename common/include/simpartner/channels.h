// LCM channel names of SPEC 5b: the contract between processes.
#pragma once

namespace simpartner::channels {

inline constexpr const char* kModel = "SIM_MODEL";                  // model_t
inline constexpr const char* kModelRequest = "SIM_MODEL_REQUEST";   // model_request_t
inline constexpr const char* kState = "SIM_STATE";                  // state_t
inline constexpr const char* kStateRequest = "SIM_STATE_REQUEST";   // state_request_t
inline constexpr const char* kStateReply = "SIM_STATE_REPLY";       // state_t
inline constexpr const char* kCommand = "SIM_COMMAND";              // command_t
inline constexpr const char* kCommandReply = "SIM_COMMAND_REPLY";   // command_reply_t
inline constexpr const char* kSensor = "SIM_SENSOR";                // sensor_reading_t
inline constexpr const char* kControl = "SIM_CONTROL";              // control_t
inline constexpr const char* kStatus = "SIM_STATUS";                // status_t
inline constexpr const char* kSync = "SIM_SYNC";                    // sync_t
inline constexpr const char* kSyncReply = "SIM_SYNC_REPLY";         // sync_reply_t
inline constexpr const char* kImage = "SIM_IMAGE";                  // image_t (simpartner-camera)
inline constexpr const char* kSoilRuts = "SIM_SOIL_RUTS";           // soil_ruts_t

}  // namespace simpartner::channels
