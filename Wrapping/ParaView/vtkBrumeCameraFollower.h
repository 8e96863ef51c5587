// SPDX-License-Identifier: BSD-3-Clause
// Camera following on the client side of ParaView's server manager: before
// every render of a render view (vtkSMViewProxy's StartEvent, which fires
// before the view updates its pipelines), each visible "Brume Radiance"
// representation with FollowCamera on sets its reconstruction's
// EyePosition to the view's camera position. The modified property makes
// the same render's update re-execute the reconstruction's view update
// wherever it runs: the built-in session, a pvserver, every process of
// mpirun pvbatch (in step, since the property reaches them all).
#ifndef vtkBrumeCameraFollower_h
#define vtkBrumeCameraFollower_h

class vtkSMProxy;

namespace vtkBrumeCameraFollower
{
/**
 * Watches the render views of every session of this process, present and
 * future (views registered later, sessions connected later). Idempotent;
 * does nothing in a process without a server manager (pvserver).
 */
void Install();

/**
 * What the observer does before `view` renders: for each of its visible
 * "Brume Radiance" representations with FollowCamera on whose input is a
 * reconstruction with view-dependent textures (or textures not known
 * yet), EyePosition := the view's camera position, when it differs in
 * single precision (the reconstruction's). Returns the number of
 * reconstructions moved.
 */
int Follow(vtkSMProxy* view);
}

#endif
