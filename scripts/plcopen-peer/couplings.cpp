// Drives pyplcopen's MC_GearIn, MC_GearInPos, MC_PhasingRelative,
// MC_MoveSuperimposed, MC_HaltSuperimposed and MC_DigitalCamSwitch
// function blocks (fb::FbGearIn, fb::FbGearInPos, fb::FbPhasingRelative,
// fb::FbMoveSuperimposed, fb::FbHaltSuperimposed, fb::FbDigitalCamSwitch
// from the peer's header-only core) and prints CSV traces that ecam's
// couplings are compared against
// (crates/ecam-engine/tests/it/plcopen_peer_couplings.rs). This program
// only calls the peer; none of its code is copied here.
//
// Usage: couplings CASE      one trace as CSV on stdout
//        couplings --list    the case names
//
// One cycle of the peer is one tick of ecam; the peer's velocities are
// per cycle, its accelerations per cycle², so ecam runs these cases with
// 1 s ticks (units/s = units/cycle). The cam-switch cases use the peer's
// 1 ms task period and feed velocities in units/s.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "axis/group.h"
#include "axis/state.h"
#include "fb/io.h"
#include "fb/motion.h"
#include "fb/sync.h"

using namespace plcopen::core;

namespace {

// A master, a slave and their group (MC_GearIn needs both in one enabled group).
struct Rig
{
    axis::AxisModel master{};
    axis::AxisModel slave{};
    axis::AxisGroup group{};
    bool ok = true;

    Rig()
    {
        ok = master.set_power(true) == rt::ErrorCode::ok &&
             slave.set_power(true) == rt::ErrorCode::ok &&
             group.add_axis(master) == rt::ErrorCode::ok &&
             group.add_axis(slave) == rt::ErrorCode::ok && group.enable() == rt::ErrorCode::ok;
    }
};

int fail(const char *what)
{
    std::fprintf(stderr, "%s\n", what);
    return 2;
}

// MC_GearIn at 3/2 without dynamics (the peer locks at once); the master is
// set each cycle: 0 .. 7400 in steps of 37, then back to -3700.
int gear_in_3_2()
{
    Rig rig;
    if(!rig.ok || rig.slave.set_position(1000) != rt::ErrorCode::ok) return fail("setup");
    fb::FbGearIn gear;
    gear.master_ref = &rig.master;
    gear.slave_ref = &rig.slave;
    gear.ratio_numerator = 3;
    gear.ratio_denominator = 2;
    gear.execute = true;
    std::printf("# case=gear_in_3_2 ratio=3/2 slave_start=1000 master=0..7400 step 37, back to -3700\n");
    std::printf("cycle,master,slave,in_gear,busy,active,error\n");
    gear.call();
    int cycle = 0;
    auto step = [&](double m) {
        if(cycle > 0 && rig.master.set_position(m) != rt::ErrorCode::ok) return false;
        rig.master.cycle();
        rig.slave.cycle();
        gear.call();
        std::printf("%d,%.0f,%.6f,%d,%d,%d,%d\n", cycle, m, rig.slave.snapshot().command_position,
                    gear.in_gear, gear.outputs.busy, gear.outputs.active, gear.outputs.error);
        ++cycle;
        return true;
    };
    for(int m = 0; m <= 7400; m += 37)
        if(!step(m)) return fail("master set_position");
    for(int m = 7400 - 37; m >= -3700; m -= 37)
        if(!step(m)) return fail("master set_position");
    return 0;
}

// MC_GearInPos at 2/1 to (master 20000, slave 16000) from 8000 before; the
// master runs at 250 counts per cycle (set each cycle, fed as its actual
// position and velocity).
int gear_in_pos_2_1()
{
    Rig rig;
    if(!rig.ok) return fail("setup");
    fb::FbGearInPos gear;
    gear.master_ref = &rig.master;
    gear.slave_ref = &rig.slave;
    gear.ratio_numerator = 2;
    gear.ratio_denominator = 1;
    gear.master_sync_position = 20000;
    gear.slave_sync_position = 16000;
    gear.master_start_distance = 8000;
    gear.master_value_source = axis::MasterValueSource::actual;
    gear.velocity = 2000;
    gear.acceleration = 100;
    gear.deceleration = 100;
    gear.jerk = 1e6;
    gear.execute = true;
    std::printf("# case=gear_in_pos_2_1 ratio=2/1 master_sync=20000 slave_sync=16000 "
                "master_start_distance=8000 master=0..30000 step 250\n");
    std::printf("cycle,master,slave,start_sync,in_sync,busy,active,error\n");
    int cycle = 0;
    for(int m = 0; m <= 30000; m += 250) {
        if(rig.master.set_position(m) != rt::ErrorCode::ok ||
           rig.master.set_actual_feedback(m, 250.0) != rt::ErrorCode::ok)
            return fail("master");
        rig.master.cycle();
        if(rig.master.set_actual_feedback(m, 250.0) != rt::ErrorCode::ok) return fail("feedback");
        rig.slave.cycle();
        gear.call();
        std::printf("%d,%d,%.6f,%d,%d,%d,%d,%d\n", cycle, m, rig.slave.snapshot().command_position,
                    gear.start_sync, gear.in_sync, gear.outputs.busy, gear.outputs.active,
                    gear.outputs.error);
        ++cycle;
    }
    return 0;
}

// MC_PhasingRelative by 1000 on a 1:1 gear (velocity 20, acceleration 1,
// deceleration 1 per cycle, a jerk so large the profile is a trapezoid);
// the master is set each cycle, 10 counts further.
int phasing_relative_1000()
{
    Rig rig;
    if(!rig.ok) return fail("setup");
    fb::FbGearIn gear;
    gear.master_ref = &rig.master;
    gear.slave_ref = &rig.slave;
    gear.execute = true;
    fb::FbPhasingRelative phasing;
    phasing.master_ref = &rig.master;
    phasing.slave_ref = &rig.slave;
    phasing.phase_shift = 1000;
    phasing.velocity = 20;
    phasing.acceleration = 1;
    phasing.deceleration = 1;
    phasing.jerk = 1000;
    std::printf("# case=phasing_relative_1000 gear=1/1 shift=1000 velocity=20 acceleration=1 "
                "deceleration=1 jerk=1000 master=0,10,20.. phasing from cycle 5\n");
    std::printf("cycle,master,slave,absolute_phase_shift,covered_phase_shift,done,busy,active\n");
    for(int cycle = 0; cycle <= 120; ++cycle) {
        const double m = 10.0 * cycle;
        if(rig.master.set_position(m) != rt::ErrorCode::ok) return fail("master");
        rig.master.cycle();
        rig.slave.cycle();
        gear.call();
        phasing.execute = cycle >= 5;
        phasing.call();
        std::printf("%d,%.0f,%.6f,%.6f,%.6f,%d,%d,%d\n", cycle, m,
                    rig.slave.snapshot().command_position, phasing.absolute_phase_shift,
                    phasing.covered_phase_shift, phasing.outputs.done, phasing.outputs.busy,
                    phasing.outputs.active);
    }
    return 0;
}

// MC_MoveSuperimposed of 777 on an axis at standstill (velocity 15,
// acceleration 1, deceleration 0.5 per cycle); with `halt` an
// MC_HaltSuperimposed (deceleration 2) at cycle 30.
int move_superimposed(bool halt)
{
    Rig rig;
    if(!rig.ok) return fail("setup");
    fb::FbMoveSuperimposed move;
    move.axis_ref = &rig.slave;
    move.distance = 777;
    move.velocity = 15;
    move.acceleration = 1;
    move.deceleration = 0.5;
    move.jerk = 1000;
    fb::FbHaltSuperimposed stop;
    stop.axis_ref = &rig.slave;
    stop.deceleration = 2;
    stop.jerk = 1000;
    std::printf("# case=%s distance=777 velocity=15 acceleration=1 deceleration=0.5 jerk=1000%s\n",
                halt ? "halt_superimposed" : "move_superimposed",
                halt ? " halt at cycle 30 deceleration=2" : "");
    std::printf("cycle,slave,covered_distance,done,busy,active\n");
    move.execute = true;
    move.call();
    for(int cycle = 1; cycle <= 160; ++cycle) {
        if(halt && cycle == 30) {
            stop.execute = true;
            stop.call();
        }
        rig.slave.cycle();
        move.call();
        std::printf("%d,%.6f,%.6f,%d,%d,%d\n", cycle, rig.slave.snapshot().command_position,
                    move.covered_distance, move.outputs.done, move.outputs.busy,
                    move.outputs.active);
    }
    return 0;
}

// MC_DigitalCamSwitch on an axis whose actual position runs 10 units per
// 1 ms cycle (10 000 units/s), modulo 1000, three periods. Tracks 1–4:
// 200..300; over the wrap 900..100; a time cam at 500 for 5 ms; 600..700
// with on and off compensation (`unequal`: -5 ms on, -3 ms off; else -2 ms
// both).
int cam_switch(bool unequal)
{
    axis::AxisModel axis{};
    if(axis.set_power(true) != rt::ErrorCode::ok) return fail("setup");
    fb::CamSwitchAction actions[4]{};
    actions[0] = {1, 200, 300, 1000};
    actions[1] = {2, 900, 100, 1000};
    actions[2] = {3, 500, 500, 1000};
    actions[2].cam_switch_mode = fb::CamSwitchAction::Mode::time;
    actions[2].duration_ns = 5000000;
    actions[3] = {4, 600, 700, 1000};
    fb::CamTrackOption options[4]{};
    options[3].on_compensation_ns = unequal ? -5000000 : -2000000;
    options[3].off_compensation_ns = unequal ? -3000000 : -2000000;
    bool outputs[4]{};
    fb::FbDigitalCamSwitch block;
    block.axis_ref = &axis;
    block.switches = {actions, 4};
    block.outputs = {outputs, 4};
    block.track_options = {options, 4};
    block.value_source = axis::MasterValueSource::actual;
    block.enable = true;
    std::printf("# case=%s modulo=1000 tracks 1:200..300 2:900..100 3:time 500 5ms "
                "4:600..700 compensation on %s off %s; 10 units per 1 ms cycle\n",
                unequal ? "cam_switch_unequal_compensation" : "cam_switch_modulo",
                unequal ? "-5ms" : "-2ms", unequal ? "-3ms" : "-2ms");
    std::printf("cycle,position,tracks\n");
    for(int cycle = 0; cycle <= 300; ++cycle) {
        const double p = 10.0 * cycle;
        if(axis.set_actual_feedback(p, 10000.0) != rt::ErrorCode::ok) return fail("feedback");
        block.call(1000000);
        if(!block.in_operation) return fail("not in operation");
        unsigned bits = 0;
        for(unsigned t = 0; t < 4; ++t)
            if(outputs[t]) bits |= 1u << t;
        std::printf("%d,%.0f,%u\n", cycle, p, bits);
    }
    return 0;
}

const char *CASES[] = {"gear_in_3_2",       "gear_in_pos_2_1",   "phasing_relative_1000",
                       "move_superimposed", "halt_superimposed", "cam_switch_modulo",
                       "cam_switch_unequal_compensation"};

}  // namespace

int main(int argc, char **argv)
{
    if(argc == 2 && std::strcmp(argv[1], "--list") == 0) {
        for(const char *c : CASES) std::printf("%s\n", c);
        return 0;
    }
    if(argc == 2) {
        const char *c = argv[1];
        if(std::strcmp(c, "gear_in_3_2") == 0) return gear_in_3_2();
        if(std::strcmp(c, "gear_in_pos_2_1") == 0) return gear_in_pos_2_1();
        if(std::strcmp(c, "phasing_relative_1000") == 0) return phasing_relative_1000();
        if(std::strcmp(c, "move_superimposed") == 0) return move_superimposed(false);
        if(std::strcmp(c, "halt_superimposed") == 0) return move_superimposed(true);
        if(std::strcmp(c, "cam_switch_modulo") == 0) return cam_switch(false);
        if(std::strcmp(c, "cam_switch_unequal_compensation") == 0) return cam_switch(true);
    }
    std::fprintf(stderr, "usage: couplings CASE | --list\n");
    return 2;
}
