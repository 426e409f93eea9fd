// Everything of the event kernel in one include.
#pragma once

#include "latsim/des/event_queue.hpp"
#include "latsim/des/inline_function.hpp"
#include "latsim/des/process.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/des/signal.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/des/time.hpp"
