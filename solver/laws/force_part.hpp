#pragma once
// The force, torque and heat parts a parcel receives, per real particle. Contact is the DEM's
// own and always computed; the others exist when the effect that computes them is on.
namespace dustlift {

enum class ForcePart { None, Contact, Drag, Magnus, Pressure, FluidTorque, Heat, AddedMass };

}  // namespace dustlift
