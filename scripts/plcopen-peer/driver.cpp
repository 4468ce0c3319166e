// Drives pyplcopen's MC_CamTableSelect / MC_CamIn function blocks
// (fb::FbCamTableSelect, fb::FbCamIn from the peer's header-only core) and
// prints CSV traces that ecam's PLCopen facade is compared against
// (crates/ecam-engine/tests/it/plcopen_peer.rs). This program only calls
// the peer; none of its code is copied here.
//
// Usage: driver CASE          one trace as CSV on stdout
//        driver --list        the case names
//        driver --tables      the cam tables as CSV
//        driver --bench [N]   ns per FB cycle (513-point and 4-point cams)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "axis/group.h"
#include "axis/state.h"
#include "exec/sync.h"
#include "fb/sync.h"

using namespace plcopen::core;

namespace {

using Points = std::vector<exec::CamPoint>;

// Document 001's Repeat-cam example: master 0..30000, slave 500..2000.
Points doc001()
{
    return {{0, 500}, {10000, 1500}, {20000, 1000}, {30000, 2000}};
}

// A 513-point periodic cam with a stroke: 2000 over 512 steps of 100 master
// counts plus a 300-count sine, so the first (0) and last (2000) values differ.
Points cam513()
{
    Points p;
    for(int i = 0; i <= 512; ++i) {
        const double s = 2000.0 * i / 512.0 + 300.0 * std::sin(2.0 * M_PI * i / 512.0);
        p.push_back({100.0 * i, std::round(s)});
    }
    return p;
}

Points cam4()
{
    return {{0, 0}, {1000, 400}, {2000, 1600}, {3000, 2000}};
}

struct Case
{
    const char *name;
    const char *table;
    bool periodic;
    bool master_absolute;
    bool slave_absolute;
    axis::CamStartMode start_mode;
    double master_scaling;
    double master_offset;
    double slave_start;
    // Master positions: from `first`, in steps of `step`, to `turn`, then
    // (if `back` != turn) back down to `back`.
    double first, step, turn, back;
};

const Case CASES[] = {
    {"periodic_absolute", "cam513", true, true, true, axis::CamStartMode::absolute, 1, 0, 0,
     0, 997, 3 * 51200, 3 * 51200},
    {"periodic_absolute_reversal", "cam513", true, true, true, axis::CamStartMode::absolute, 1,
     0, 0, 0, 997, 80000, -30000},
    {"periodic_slave_relative_5000", "cam513", true, false, false, axis::CamStartMode::absolute,
     1, 0, 5000, 0, 997, 3 * 51200, 3 * 51200},
    {"doc001_periodic_absolute", "doc001", true, true, true, axis::CamStartMode::absolute, 1, 0,
     0, 0, 625, 70000, 70000},
    {"non_periodic_master_absolute", "doc001", false, true, true, axis::CamStartMode::absolute,
     1, 0, 0, 0, 1250, 40000, 40000},
    {"non_periodic_master_absolute_reversal", "doc001", false, true, true,
     axis::CamStartMode::absolute, 1, 0, 0, 0, 1250, 40000, 5000},
    {"master_scaling_2_offset_1000", "doc001", true, true, true, axis::CamStartMode::absolute, 2,
     1000, 0, 0, 625, 80000, 80000},
    {"slave_relative_adds_start_5000", "doc001", true, false, false,
     axis::CamStartMode::absolute, 1, 0, 5000, 0, 750, 70000, 70000},
    {"start_mode_relative_5000", "doc001", true, true, true, axis::CamStartMode::relative, 1, 0,
     5000, 0, 750, 70000, 70000},
};

Points table_named(const std::string &name)
{
    if(name == "doc001") return doc001();
    if(name == "cam513") return cam513();
    return cam4();
}

std::vector<double> masters(const Case &c)
{
    std::vector<double> m;
    for(double x = c.first; x <= c.turn; x += c.step) m.push_back(x);
    if(c.back < c.turn) {
        for(double x = m.back() - c.step; x >= c.back; x -= c.step) m.push_back(x);
    }
    return m;
}

const char *start_mode_name(axis::CamStartMode m)
{
    return m == axis::CamStartMode::relative ? "relative" : "absolute";
}

// The master, the slave and their group; the master is a virtual axis whose
// position the driver sets each cycle (standstill between cycles).
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

int run_case(const Case &c)
{
    static Rig rig;
    if(!rig.ok) {
        std::fprintf(stderr, "axis setup failed\n");
        return 2;
    }
    const Points points = table_named(c.table);
    const std::vector<double> m = masters(c);
    if(rig.master.set_position(m.front()) != rt::ErrorCode::ok ||
       rig.slave.set_position(c.slave_start) != rt::ErrorCode::ok) {
        std::fprintf(stderr, "set_position failed\n");
        return 2;
    }
    fb::FbCamTableSelect select;
    select.master_ref = &rig.master;
    select.slave_ref = &rig.slave;
    select.cam_table = exec::CamTableView{points.data(), points.size(), false};
    select.periodic = c.periodic;
    select.master_absolute = c.master_absolute;
    select.slave_absolute = c.slave_absolute;
    select.execute = true;
    select.call();
    if(!select.done) {
        std::fprintf(stderr, "MC_CamTableSelect failed: error %d\n", int(select.error_id));
        return 2;
    }
    fb::FbCamIn cam;
    cam.master_ref = &rig.master;
    cam.slave_ref = &rig.slave;
    cam.cam_table_id = select.cam_table_id;
    cam.master_scaling = c.master_scaling;
    cam.master_offset = c.master_offset;
    cam.start_mode = c.start_mode;
    cam.execute = true;
    std::printf("# case=%s table=%s periodic=%d master_absolute=%d slave_absolute=%d "
                "start_mode=%s master_scaling=%g master_offset=%g slave_start=%g\n",
                c.name, c.table, c.periodic, c.master_absolute, c.slave_absolute,
                start_mode_name(c.start_mode), c.master_scaling, c.master_offset, c.slave_start);
    std::printf("cycle,master,slave,in_sync,end_of_profile,active,busy,error\n");
    cam.call();  // rising Execute: the coupling is submitted
    for(std::size_t i = 0; i < m.size(); ++i) {
        if(i > 0 && rig.master.set_position(m[i]) != rt::ErrorCode::ok) {
            std::fprintf(stderr, "master set_position failed at %g\n", m[i]);
            return 2;
        }
        rig.master.cycle();
        rig.slave.cycle();
        cam.call();
        std::printf("%zu,%.0f,%.6f,%d,%d,%d,%d,%d\n", i, m[i],
                    rig.slave.snapshot().command_position, cam.in_sync, cam.end_of_profile,
                    cam.outputs.active, cam.outputs.busy, cam.outputs.error);
    }
    return 0;
}

// ns per FB cycle: master set, both axes cycled, MC_CamIn called (what a
// PLC task does per cycle for one coupled pair).
int bench(const char *table, long cycles)
{
    static Rig rigs[2];
    Rig &rig = rigs[std::strcmp(table, "cam513") == 0 ? 0 : 1];
    const Points points = table_named(table);
    fb::FbCamTableSelect select;
    select.master_ref = &rig.master;
    select.slave_ref = &rig.slave;
    select.cam_table = exec::CamTableView{points.data(), points.size(), false};
    select.periodic = true;
    select.execute = true;
    select.call();
    fb::FbCamIn cam;
    cam.master_ref = &rig.master;
    cam.slave_ref = &rig.slave;
    cam.cam_table_id = select.cam_table_id;
    cam.execute = true;
    cam.call();
    const double span = points.back().master - points.front().master;
    const double step = span / 1000.0 * 7.3;  // visits every segment over the run
    double x = 0.0;
    double sink = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for(long i = 0; i < cycles; ++i) {
        x += step;
        rig.master.set_position(x);
        rig.master.cycle();
        rig.slave.cycle();
        cam.call();
        sink += rig.slave.snapshot().command_position;
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double ns =
        std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(cycles);
    std::printf("tick-peer,%s,%zu points,%ld cycles,%.1f ns/cycle,in_sync=%d,checksum=%.0f\n",
                table, points.size(), cycles, ns, cam.in_sync, sink);
    return cam.in_sync ? 0 : 2;
}

}  // namespace

int main(int argc, char **argv)
{
    if(argc >= 2 && std::strcmp(argv[1], "--list") == 0) {
        for(const Case &c : CASES) std::printf("%s\n", c.name);
        return 0;
    }
    if(argc >= 2 && std::strcmp(argv[1], "--tables") == 0) {
        std::printf("# The cam tables the traces use (master,slave points).\ntable,master,slave\n");
        for(const char *name : {"doc001", "cam513"}) {
            for(const exec::CamPoint &p : table_named(name)) {
                std::printf("%s,%.0f,%.0f\n", name, p.master, p.slave);
            }
        }
        return 0;
    }
    if(argc >= 2 && std::strcmp(argv[1], "--bench") == 0) {
        const long n = argc >= 3 ? std::atol(argv[2]) : 1000000;
        if(n <= 0) {
            std::fprintf(stderr, "--bench N: N must be positive\n");
            return 2;
        }
        const int a = bench("cam513", n);
        const int b = bench("cam4", n);
        return a != 0 ? a : b;
    }
    if(argc == 2) {
        for(const Case &c : CASES) {
            if(std::strcmp(argv[1], c.name) == 0) return run_case(c);
        }
    }
    std::fprintf(stderr, "usage: driver CASE | --list | --bench [N]\n");
    return 2;
}
