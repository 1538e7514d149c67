#include "simpartner/bus_url.h"

namespace simpartner {

std::string WithReceiveBuffer(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=4194304";
}

}  // namespace simpartner
