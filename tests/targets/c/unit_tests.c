/* Unit tests of the generated C helpers: J1939, lookups, pack/unpack errors, counters, physical
 * range rules, the VIN text helpers and the receive monitor. Expected values come from the
 * protocol document (IDs, addresses, fault codes) and the shared encoding rules. */
#include <stdio.h>
#include <string.h>

#include "kaiwo_gateway.h"

static int failures = 0;
static int checks = 0;
#define CHECK(cond)                                                                                \
    do {                                                                                           \
        checks++;                                                                                  \
        if (!(cond)) {                                                                             \
            failures++;                                                                            \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);               \
        }                                                                                          \
    } while (0)

static void test_j1939(void) {
    kaiwo_gateway_j1939_id_t id = kaiwo_gateway_j1939_decompose(0x1801B0A0u);
    kaiwo_gateway_msg_t found[8];
    CHECK(id.priority == 6u && id.pgn == 0x0100u && id.sa == 0xA0u && id.da == 0xB0u && !id.is_pdu2);
    id = kaiwo_gateway_j1939_decompose(0x18FFAF00u); /* device ID: PDU2 broadcast, PGN 0xFFAF */
    CHECK(id.priority == 6u && id.pgn == 0xFFAFu && id.sa == 0x00u && id.da == 0xFFu && id.is_pdu2);
    CHECK(kaiwo_gateway_j1939_compose(6u, 0x0100u, 0xA0u, 0xB0u) == 0x1801B0A0u);
    CHECK(kaiwo_gateway_j1939_compose(6u, 0xFFAFu, 0x00u, 0x12u) == 0x18FFAF00u); /* DA ignored for PDU2 */
    CHECK(kaiwo_gateway_j1939_compose(3u, 0x1300u, 0xB0u, 0xA0u) == 0x0C13A0B0u);
    CHECK(KAIWO_GATEWAY_VEHICLE_FAULT_FRAME_ID == 0x1813A0B0u);
    CHECK(KAIWO_GATEWAY_VEHICLE_FAULT_PGN == 0x1300u && KAIWO_GATEWAY_VEHICLE_FAULT_SA == 0xB0u && KAIWO_GATEWAY_VEHICLE_FAULT_DA == 0xA0u);
    CHECK(KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_CYCLE_MS == 20u && KAIWO_GATEWAY_DEVICE_ID_CYCLE_MS == 500u);
    CHECK(kaiwo_gateway_lookup_id(0x1801B0C0u) == KAIWO_GATEWAY_MSG_RGATE_EPS_COMMAND);
    CHECK(kaiwo_gateway_lookup_id(0x1801B0C1u) == KAIWO_GATEWAY_MSG_NONE);
    CHECK(kaiwo_gateway_lookup_id(0x0C01B0C0u) == KAIWO_GATEWAY_MSG_NONE);
    CHECK(kaiwo_gateway_lookup_id_any_priority(0x0C01B0C0u) == KAIWO_GATEWAY_MSG_RGATE_EPS_COMMAND);
    /* PGN 0x0100 is sent by AUTOCAR, R-GATE and Tele: three matches, in document order. */
    CHECK(kaiwo_gateway_lookup_pgn(0x0100u, found, 8) == 3u);
    CHECK(found[0] == KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND && found[1] == KAIWO_GATEWAY_MSG_RGATE_EPS_COMMAND &&
          found[2] == KAIWO_GATEWAY_MSG_TELE_EPS_COMMAND);
    CHECK(kaiwo_gateway_lookup_pgn(0x0100u, found, 1) == 3u);
    CHECK(kaiwo_gateway_lookup_pgn(0xFFAFu, NULL, 0) == 1u);
    CHECK(kaiwo_gateway_lookup_pgn(0x1234u, found, 8) == 0u);
    CHECK(kaiwo_gateway_msg_info(KAIWO_GATEWAY_MSG_NONE) == NULL);
    CHECK(strcmp(kaiwo_gateway_msg_info(KAIWO_GATEWAY_MSG_DEVICE_ID)->name, "device_id") == 0);
}

static void test_pack_unpack(void) {
    uint8_t buf[8];
    kaiwo_gateway_autocar_eps_command_t eps = kaiwo_gateway_autocar_eps_command_init();
    kaiwo_gateway_front_sensor_distance_1_t fs = kaiwo_gateway_front_sensor_distance_1_init();
    kaiwo_gateway_autocar_eps_command_t back;
    eps.eps_ctrl_mode = KAIWO_GATEWAY_EPS_MODE_CMD_AUTO_ANGLE;
    eps.counter = 7u;
    eps.steering_angle_cmd = 10800u; /* 0 deg */
    eps.checksum = 0x55u;            /* ignored: pack computes it */
    CHECK(kaiwo_gateway_autocar_eps_command_pack(buf, 7u, &eps) == KAIWO_GATEWAY_ERR_LENGTH);
    CHECK(kaiwo_gateway_autocar_eps_command_pack(buf, sizeof buf, &eps) == KAIWO_GATEWAY_OK);
    CHECK(buf[0] == 0x20u && buf[1] == 0x07u && buf[3] == 0x30u && buf[4] == 0x2Au && buf[5] == 0u && buf[6] == 0u);
    CHECK(buf[7] == (uint8_t)(buf[0] ^ buf[1] ^ buf[2] ^ buf[3] ^ buf[4] ^ buf[5] ^ buf[6]));
    CHECK(kaiwo_gateway_autocar_eps_command_unpack(&back, buf, 7u) == KAIWO_GATEWAY_ERR_LENGTH);
    CHECK(kaiwo_gateway_autocar_eps_command_unpack(&back, buf, 8u) == KAIWO_GATEWAY_OK);
    CHECK(back.steering_angle_cmd == 10800u && back.counter == 7u && back.checksum == buf[7]);
    buf[7] ^= 0x01u;
    CHECK(kaiwo_gateway_autocar_eps_command_unpack(&back, buf, 8u) == KAIWO_GATEWAY_ERR_CHECKSUM);
    CHECK(back.steering_angle_cmd == 10800u); /* still decoded */
    /* raw level: any value that fits the bits; a 10-bit field rejects 1024 */
    fs.sensor_1_distance = 1023u;
    CHECK(kaiwo_gateway_front_sensor_distance_1_pack(buf, 8u, &fs) == KAIWO_GATEWAY_OK);
    fs.sensor_1_distance = 1024u;
    CHECK(kaiwo_gateway_front_sensor_distance_1_pack(buf, 8u, &fs) == KAIWO_GATEWAY_ERR_RANGE);
    fs.sensor_1_distance = 0u;
    fs.counter = 16u;
    CHECK(kaiwo_gateway_front_sensor_distance_1_pack(buf, 8u, &fs) == KAIWO_GATEWAY_ERR_RANGE);
    /* reserved bits are sent as 0 even when the received frame had them set */
    {
        const uint8_t in[8] = {0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu};
        kaiwo_gateway_front_sensor_distance_2_t f2;
        CHECK(kaiwo_gateway_front_sensor_distance_2_unpack(&f2, in, 8u) == KAIWO_GATEWAY_OK);
        CHECK(kaiwo_gateway_front_sensor_distance_2_pack(buf, 8u, &f2) == KAIWO_GATEWAY_OK);
        CHECK(buf[3] == 0x3Fu && buf[5] == 0x07u && buf[6] == 0x00u && buf[7] == 0xF0u);
    }
}

static void test_counters_and_physical(void) {
    {
        /* 252 x 0.05 - 9 is 3.6000000000000014 in doubles, a hair above the documented 3.6: the
         * shared rule's tolerance (|factor| x 1e-9) lets every decoded value re-encode. */
        uint8_t raw = 0u;
        const double top = kaiwo_gateway_driving_state_current_accel_decode(252u);
        CHECK(top > 3.6);
        CHECK(kaiwo_gateway_driving_state_current_accel_encode(top, &raw) == KAIWO_GATEWAY_OK && raw == 252u);
        CHECK(kaiwo_gateway_driving_state_current_accel_encode(3.605, &raw) == KAIWO_GATEWAY_ERR_RANGE);
    }
    uint16_t raw16 = 0;
    uint8_t raw8 = 0;
    CHECK(kaiwo_gateway_front_sensor_distance_1_counter_next(14u) == 15u);
    CHECK(kaiwo_gateway_front_sensor_distance_1_counter_next(15u) == 0u);
    CHECK(kaiwo_gateway_autocar_eps_command_counter_next(254u) == 255u);
    CHECK(kaiwo_gateway_autocar_eps_command_counter_next(255u) == 0u);
    /* steering angle: factor 0.1, offset -1080, range [-1080, 1080] */
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(0.0, &raw16) == KAIWO_GATEWAY_OK && raw16 == 10800u);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(-1079.95, &raw16) == KAIWO_GATEWAY_OK && raw16 == 1u);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(1080.05, &raw16) == KAIWO_GATEWAY_ERR_RANGE);
    {
        volatile double zero = 0.0;
        raw16 = 77u;
        CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(zero / zero, &raw16) == KAIWO_GATEWAY_ERR_RANGE && raw16 == 77u);
    }
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(1e300, &raw16) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_decode(21600u) == 1080.0);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_decode_fixed(1u) == -107990); /* x100 */
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode_fixed(-107995, &raw16) == KAIWO_GATEWAY_OK && raw16 == 1u);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode_fixed(-107985, &raw16) == KAIWO_GATEWAY_OK && raw16 == 2u);
    CHECK(kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode_fixed(108001, &raw16) == KAIWO_GATEWAY_ERR_RANGE);
    /* accel: factor 0.02, offset -9, tie -8.99 rounds away from zero to raw 1 (-8.98) */
    CHECK(kaiwo_gateway_autocar_speed_command_accel_cmd_encode(-8.99, &raw16) == KAIWO_GATEWAY_OK && raw16 == 1u);
    CHECK(kaiwo_gateway_autocar_speed_command_accel_cmd_encode(3.61, &raw16) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_autocar_speed_command_accel_cmd_encode_fixed(-899, &raw16) == KAIWO_GATEWAY_OK && raw16 == 1u);
    /* specials: 0x3FF = no obstacle, outside the documented 0..500 cm but encodable */
    CHECK(kaiwo_gateway_front_sensor_distance_1_sensor_1_distance_encode(1023.0, &raw16) == KAIWO_GATEWAY_OK &&
          raw16 == KAIWO_GATEWAY_FRONT_SENSOR_DISTANCE_1_SENSOR_1_DISTANCE_NO_OBSTACLE);
    CHECK(kaiwo_gateway_front_sensor_distance_1_sensor_1_distance_encode(501.0, &raw16) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_driving_state_motor_speed_ratio_encode(0.0, &raw8) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_driving_state_motor_speed_ratio_encode(256.0, &raw8) == KAIWO_GATEWAY_OK && raw8 == 255u);
    CHECK(kaiwo_gateway_driving_state_motor_speed_ratio_encode_fixed(2560, &raw8) == KAIWO_GATEWAY_OK && raw8 == 255u);
    CHECK(strcmp(kaiwo_gateway_gear_name(KAIWO_GATEWAY_GEAR_REVERSE), "reverse") == 0);
    CHECK(kaiwo_gateway_gear_name(9u) == NULL);
}

static void test_vin(void) {
    const char *vin = "LKLA6G1H8LA000205";
    uint8_t frames[3][8];
    kaiwo_gateway_device_id_t tmpl = kaiwo_gateway_device_id_init();
    kaiwo_gateway_device_id_text_rx_t rx;
    char out[32];
    tmpl.device_type = KAIWO_GATEWAY_DEVICE_TYPE_VEHICLE;
    CHECK(kaiwo_gateway_device_id_text_split(vin, strlen(vin), &tmpl, frames) == KAIWO_GATEWAY_OK);
    /* from the document's example: frame 1 carries "LKLA6G1", index in bits 6..7 of byte 0 */
    CHECK(frames[0][0] == 0x00u && memcmp(&frames[0][1], "LKLA6G1", 7) == 0);
    CHECK(frames[1][0] == 0x40u && memcmp(&frames[1][1], "H8LA000", 7) == 0);
    CHECK(frames[2][0] == 0x80u && memcmp(&frames[2][1], "205\0\0\0\0", 7) == 0);
    CHECK(kaiwo_gateway_device_id_text_split("LKLA6G1H8LA0002051", 18, &tmpl, frames) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_device_id_text_split("LKLA\n", 5, &tmpl, frames) == KAIWO_GATEWAY_ERR_RANGE);
    CHECK(kaiwo_gateway_device_id_text_split(vin, strlen(vin), &tmpl, frames) == KAIWO_GATEWAY_OK);
    kaiwo_gateway_device_id_text_rx_init(&rx);
    CHECK(kaiwo_gateway_device_id_text_rx_get(&rx, out, sizeof out) == KAIWO_GATEWAY_ERR_INCOMPLETE);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[2], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[0], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_get(&rx, out, sizeof out) == KAIWO_GATEWAY_ERR_INCOMPLETE);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[0], 8u) == KAIWO_GATEWAY_OK); /* repeat: same content */
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[1], 7u) == KAIWO_GATEWAY_ERR_LENGTH);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[1], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_complete(&rx));
    CHECK(kaiwo_gateway_device_id_text_rx_get(&rx, out, 17u) == KAIWO_GATEWAY_ERR_LENGTH);
    CHECK(kaiwo_gateway_device_id_text_rx_get(&rx, out, sizeof out) == KAIWO_GATEWAY_OK && strcmp(out, vin) == 0);
    {
        uint8_t other[8];
        memcpy(other, frames[1], 8);
        other[3] = 'X'; /* a different VIN's frame 2 */
        CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, other, 8u) == KAIWO_GATEWAY_ERR_INCONSISTENT);
        CHECK(!kaiwo_gateway_device_id_text_rx_complete(&rx)); /* restarted from that frame */
        memcpy(other, frames[0], 8);
        other[0] = 0x01u; /* device type remote cockpit: another sender */
        CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, other, 8u) == KAIWO_GATEWAY_ERR_INCONSISTENT);
        other[0] = 0xC0u; /* index 3: unused frame 4 */
        CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, other, 8u) == KAIWO_GATEWAY_ERR_INDEX);
    }
    kaiwo_gateway_device_id_text_rx_init(&rx);
    frames[2][6] = 'Z'; /* text after the 17th character */
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[0], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[1], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_feed(&rx, frames[2], 8u) == KAIWO_GATEWAY_OK);
    CHECK(kaiwo_gateway_device_id_text_rx_get(&rx, out, sizeof out) == KAIWO_GATEWAY_ERR_INCONSISTENT);
}

static void eps_frame(uint8_t *buf, uint8_t counter) {
    kaiwo_gateway_autocar_eps_command_t m = kaiwo_gateway_autocar_eps_command_init();
    m.counter = counter;
    m.steering_angle_cmd = 10800u;
    (void)kaiwo_gateway_autocar_eps_command_pack(buf, 8u, &m);
}

static uint32_t eps_at(kaiwo_gateway_monitor_t *mon, uint8_t counter, uint32_t t, uint8_t corrupt) {
    uint8_t buf[8];
    eps_frame(buf, counter);
    buf[7] ^= corrupt;
    return kaiwo_gateway_monitor_on_frame(mon, KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_FRAME_ID, buf, 8u, t, NULL);
}

static uint32_t speed_at(kaiwo_gateway_monitor_t *mon, uint8_t counter, uint32_t t, uint8_t corrupt) {
    uint8_t buf[8];
    kaiwo_gateway_autocar_speed_command_t sp = kaiwo_gateway_autocar_speed_command_init();
    sp.counter = counter;
    (void)kaiwo_gateway_autocar_speed_command_pack(buf, 8u, &sp);
    buf[7] ^= corrupt;
    return kaiwo_gateway_monitor_on_frame(mon, KAIWO_GATEWAY_AUTOCAR_SPEED_COMMAND_FRAME_ID, buf, 8u, t, NULL);
}

/* The rules by hand (generator/canspec/runtime/monitor.py); the shared sequence vectors test them in full. */
static void test_monitor(void) {
    kaiwo_gateway_monitor_t mon;
    uint8_t buf[8];
    kaiwo_gateway_any_t any;
    const kaiwo_gateway_rx_state_t *st = &mon.msgs[KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND];
    const uint32_t t = 0xFFFFFF00u; /* timestamps wrap around during the test */
    kaiwo_gateway_monitor_init(&mon);
    CHECK(mon.counter_tolerance == 1u && mon.valid_after == 2u && st->timeout_ms == 60u && !st->armed);
    kaiwo_gateway_monitor_expect(&mon, KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND, t, 3u); /* 60 ms */
    eps_frame(buf, 0u);
    CHECK(kaiwo_gateway_monitor_on_frame(&mon, KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_FRAME_ID, buf, 8u, t, &any) == 0u);
    CHECK(any.msg == KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND && any.u.autocar_eps_command.steering_angle_cmd == 10800u);
    CHECK(st->state == KAIWO_GATEWAY_RX_INIT);
    CHECK(eps_at(&mon, 1u, t + 20u, 0u) == 0u && st->state == KAIWO_GATEWAY_RX_VALID);
    CHECK(eps_at(&mon, 1u, t + 40u, 0u) == KAIWO_GATEWAY_RX_COUNTER_REPEAT && st->state == KAIWO_GATEWAY_RX_INVALID);
    CHECK(eps_at(&mon, 3u, t + 60u, 0u) == 0u && st->state == KAIWO_GATEWAY_RX_INVALID); /* one frame lost: in sequence */
    CHECK(eps_at(&mon, 4u, t + 80u, 0u) == KAIWO_GATEWAY_RX_RECOVERED && st->state == KAIWO_GATEWAY_RX_VALID);
    CHECK(eps_at(&mon, 7u, t + 100u, 0u) == KAIWO_GATEWAY_RX_COUNTER_JUMP && st->state == KAIWO_GATEWAY_RX_INVALID);
    CHECK(st->frames == 6u && st->accepted == 5u && st->counter_repeats == 1u && st->counter_jumps == 1u && st->lost_frames == 1u);
    /* a checksum failure: code 05 until an accepted frame; the bad frame's counter is not stored */
    CHECK(eps_at(&mon, 8u, t + 120u, 0xFFu) == KAIWO_GATEWAY_RX_CHECKSUM);
    CHECK(kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == KAIWO_GATEWAY_UNMANNED_ENTRY_FAULT_EPS_COMMAND_XOR_ERROR);
    CHECK((int)kaiwo_gateway_monitor_remote_entry_fault(&mon) == 5);
    CHECK(eps_at(&mon, 9u, t + 140u, 0u) == 0u && st->lost_frames == 2u); /* 7 -> 9 */
    CHECK(kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == KAIWO_GATEWAY_UNMANNED_ENTRY_FAULT_NO_FAULT);
    CHECK(eps_at(&mon, 10u, t + 160u, 0u) == KAIWO_GATEWAY_RX_RECOVERED);
    /* speed command checksum error: code 06 */
    CHECK(speed_at(&mon, 0u, t + 150u, 0x10u) == KAIWO_GATEWAY_RX_CHECKSUM && (int)kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == 6);
    CHECK(speed_at(&mon, 0u, t + 160u, 0u) == 0u && (int)kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == 0);
    /* timeout: more than 3 x 20 ms without an accepted frame (exactly 60 is not); code 07 */
    CHECK(kaiwo_gateway_monitor_check(&mon, t + 220u) == 0u);
    CHECK(kaiwo_gateway_monitor_check(&mon, t + 221u) == KAIWO_GATEWAY_RX_TIMEOUT);
    CHECK(kaiwo_gateway_monitor_check(&mon, t + 300u) == 0u); /* reported once */
    CHECK(kaiwo_gateway_monitor_timed_out(&mon, KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND) && (int)kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == 7);
    /* a repeat after the timeout is still no new data; another counter restarts the sequence */
    CHECK(eps_at(&mon, 10u, t + 320u, 0u) == KAIWO_GATEWAY_RX_COUNTER_REPEAT && st->timed_out);
    CHECK(eps_at(&mon, 15u, t + 340u, 0u) == 0u && !st->timed_out && st->state == KAIWO_GATEWAY_RX_INVALID);
    CHECK(speed_at(&mon, 9u, t + 340u, 0u) == 0u && (int)kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == 0);
    CHECK(eps_at(&mon, 16u, t + 360u, 0u) == KAIWO_GATEWAY_RX_RECOVERED);
    /* both faults: the lower code (checksum 05) */
    CHECK(kaiwo_gateway_monitor_check(&mon, t + 500u) == KAIWO_GATEWAY_RX_TIMEOUT);
    CHECK(eps_at(&mon, 17u, t + 500u, 0x01u) == KAIWO_GATEWAY_RX_CHECKSUM && (int)kaiwo_gateway_monitor_unmanned_entry_fault(&mon) == 5);
    CHECK(st->timeouts == 2u && st->checksum_errors == 2u);
    /* frames that are no known message's, or of the wrong length */
    CHECK(kaiwo_gateway_monitor_on_frame(&mon, 0x12345678u, buf, 8u, t, NULL) == KAIWO_GATEWAY_RX_UNKNOWN_ID);
    CHECK(kaiwo_gateway_monitor_on_frame(&mon, KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_FRAME_ID, buf, 3u, t + 500u, NULL) == KAIWO_GATEWAY_RX_LENGTH);
    CHECK(mon.unknown_ids == 1u && st->length_errors == 1u);
    /* 4-bit counters wrap at 16 */
    {
        kaiwo_gateway_front_sensor_distance_1_t f = kaiwo_gateway_front_sensor_distance_1_init();
        const uint32_t fid = KAIWO_GATEWAY_FRONT_SENSOR_DISTANCE_1_FRAME_ID;
        f.counter = 15u;
        (void)kaiwo_gateway_front_sensor_distance_1_pack(buf, 8u, &f);
        CHECK(kaiwo_gateway_monitor_on_frame(&mon, fid, buf, 8u, t, NULL) == 0u);
        f.counter = kaiwo_gateway_front_sensor_distance_1_counter_next(f.counter);
        (void)kaiwo_gateway_front_sensor_distance_1_pack(buf, 8u, &f);
        CHECK(kaiwo_gateway_monitor_on_frame(&mon, fid, buf, 8u, t, NULL) == 0u);
        CHECK(kaiwo_gateway_monitor_state(&mon, KAIWO_GATEWAY_MSG_FRONT_SENSOR_DISTANCE_1) == KAIWO_GATEWAY_RX_VALID);
    }
}

int main(void) {
    test_j1939();
    test_pack_unpack();
    test_counters_and_physical();
    test_vin();
    test_monitor();
    printf("c unit tests: %d checks, %d failures\n", checks, failures);
    return failures == 0 ? 0 : 1;
}
