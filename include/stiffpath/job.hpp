// The job module in one include: the main job as a value (JobSpec, Program, prepare, run), joint files written and read.
#pragma once

#include "stiffpath/job/job_spec.hpp"
#include "stiffpath/job/program.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/joint_reader.hpp"
