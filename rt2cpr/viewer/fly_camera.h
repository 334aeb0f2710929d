// rt2cpr/viewer/fly_camera.h — the interactive viewer's first-person camera: a position, a
// heading (yaw) and a pitch about the scene's up axis, moved by keys and turned by the mouse.
//
// It renders through the camera a scene file would describe with the same numbers
// (Camera::from_file_values), and prints itself as such a `[camera]` table with every
// float's nine significant digits: pasted into a scene file, or given to `--camera`, the
// printed table gives the very camera the viewer rendered, bit for bit.
#pragma once

#include <string>

#include "rt2/scene/camera.h"

namespace rt2cpr::viewer {

class FlyCamera {
 public:
  // Starts as `start`, bit for bit where the scene file's up can be recovered (an axis, as
  // nearly every scene gives; see file_up_of), else up to rounding with its roll. Turns and
  // moves up and down about the scene's up axis, +y (scenes are y-up: scene files, glTF,
  // framed OBJs). Movement speed: `speed` units per second.
  FlyCamera(const rt2::Camera& start, float speed);

  // Moves by `seconds` at the current speed along the view direction (forward > 0), the
  // right vector (right > 0) and the up axis (up > 0); each of forward, right, up in [-1, 1].
  // Coordinates stay within +-1e15, as in a scene file.
  void move(float forward, float right, float up, float seconds);
  // Turns by a mouse motion of (dx, dy) pixels: 0.2 degrees per pixel, right and down
  // positive; the pitch stays within 89 degrees of the horizon.
  void turn(float dx, float dy);
  // Multiplies the speed by 1.25^steps (scroll wheel), within [1e-6, 1e9] units per second.
  void scale_speed(float steps);

  float speed() const { return speed_; }
  // The camera these values describe.
  rt2::Camera camera() const;
  // The camera as a scene file's table:
  //   [camera]
  //   position = [x, y, z]
  //   direction = [x, y, z]
  //   up = [x, y, z]
  //   fov = f
  std::string toml() const;

 private:
  rt2::vec4 position_, up_, north_;  // up_: +y; north_: the heading of yaw 0, perpendicular
  rt2::vec4 view_up_;                 // the camera's up: the start's until the first turn
  rt2::vec4 east_;                    // north_ x up_
  double yaw_ = 0.0, pitch_ = 0.0;    // radians
  // The view direction: the start camera's until the first turn (so that the first image
  // is the scene's camera's), then the one of yaw and pitch.
  rt2::vec4 direction_;
  float fov_ = 60.0f, speed_ = 1.0f;
};

}  // namespace rt2cpr::viewer
