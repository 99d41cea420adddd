/* The drive-by-wire ECU (node Wire_Car_ECU): takes the steering and speed commands of the
 * autonomous controller (AUTOCAR) off the bus through the receive monitor, and answers with its
 * own state messages at their cycle times; vehicle_fault carries the monitor's fault codes.
 * Everything it knows about the protocol comes from the generated headers. */
#include <string.h>

#include "board.h"
#include "can_queue.h"
#include "ecu.h"
#include "kaiwo_gateway.h"
#include "log.h"

#define MON_MSGS ((int)KAIWO_GATEWAY_MSG_COUNT)

/* The messages this ECU sends, each with its next due time. */
static const kaiwo_gateway_msg_t tx_msgs[] = {
    KAIWO_GATEWAY_MSG_EPS_STATE,       KAIWO_GATEWAY_MSG_DRIVING_STATE,   KAIWO_GATEWAY_MSG_VEHICLE_STATE_1,
    KAIWO_GATEWAY_MSG_VEHICLE_STATE_2, KAIWO_GATEWAY_MSG_VEHICLE_STATE_3, KAIWO_GATEWAY_MSG_VEHICLE_STATE_4,
    KAIWO_GATEWAY_MSG_VEHICLE_FAULT,   KAIWO_GATEWAY_MSG_VEHICLE_STATE_5,
};
#define TX_COUNT (sizeof tx_msgs / sizeof tx_msgs[0])

static kaiwo_gateway_monitor_t monitor;
static kaiwo_gateway_any_t tx[TX_COUNT]; /* the raw values each message sends next */
static uint32_t tx_due[TX_COUNT];
static int32_t steering_centideg; /* the last valid steering command, physical x 100 (integer path) */
static uint8_t gear;

void ecu_power_on(uint32_t now_ms, const uint32_t *supervised, size_t count) {
    size_t i;
    can_queue_reset();
    kaiwo_gateway_monitor_init(&monitor);
    for (i = 0u; i < count; i++) {
        kaiwo_gateway_monitor_expect(&monitor, kaiwo_gateway_lookup_id(supervised[i]), now_ms, 0u);
    }
    (void)memset(tx, 0, sizeof tx);
    for (i = 0u; i < TX_COUNT; i++) {
        tx[i].msg = tx_msgs[i];
        tx_due[i] = now_ms;
    }
    tx[0].u.eps_state = kaiwo_gateway_eps_state_init();
    tx[1].u.driving_state = kaiwo_gateway_driving_state_init();
    steering_centideg = 0;
    gear = 0u;
    log_str("BOOT t=");
    log_u32(now_ms);
    log_end();
}

static void log_codes(void) {
    log_str(" remote=");
    log_u32((uint32_t)kaiwo_gateway_monitor_remote_entry_fault(&monitor));
    log_str(" unmanned=");
    log_u32((uint32_t)kaiwo_gateway_monitor_unmanned_entry_fault(&monitor));
}

/* The decoded values this ECU acts on, taken only from a frame the monitor accepted. */
static void use_frame(const kaiwo_gateway_any_t *rx) {
    if (rx->msg == KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND) {
        steering_centideg = kaiwo_gateway_autocar_eps_command_steering_angle_cmd_decode_fixed(rx->u.autocar_eps_command.steering_angle_cmd);
        log_str(" steering_angle_cmd=");
        log_i32(steering_centideg);
        log_str("/100 mode=");
        log_u32(rx->u.autocar_eps_command.eps_ctrl_mode);
    } else if (rx->msg == KAIWO_GATEWAY_MSG_AUTOCAR_SPEED_COMMAND) {
        gear = rx->u.autocar_speed_command.gear_cmd;
        log_str(" accel_cmd=");
        log_i32(kaiwo_gateway_autocar_speed_command_accel_cmd_decode_fixed(rx->u.autocar_speed_command.accel_cmd));
        log_str("/100 gear_cmd=");
        log_u32(gear);
    } else {
        /* supervised, not acted on */
    }
}

#define REJECTED (KAIWO_GATEWAY_RX_UNKNOWN_ID | KAIWO_GATEWAY_RX_LENGTH | KAIWO_GATEWAY_RX_CHECKSUM | KAIWO_GATEWAY_RX_COUNTER_REPEAT)

static void receive(const can_frame_t *f) {
    kaiwo_gateway_any_t rx;
    uint32_t events = KAIWO_GATEWAY_RX_UNKNOWN_ID;
    rx.msg = KAIWO_GATEWAY_MSG_NONE;
    if (f->extended) { /* every message of this protocol has a 29-bit ID: a standard frame is none of them */
        events = kaiwo_gateway_monitor_on_frame(&monitor, f->id, f->data, f->dlc, f->stamp_ms, &rx);
    }
    log_str("RX t=");
    log_u32(f->stamp_ms);
    log_str(" id=");
    log_hex(f->id, 8u);
    log_str(" events=");
    log_hex(events, 2u);
    log_str(" state=");
    log_u32(kaiwo_gateway_monitor_state(&monitor, rx.msg));
    log_codes();
    if ((events & REJECTED) == 0u) {
        use_frame(&rx);
    }
    log_end();
}

void ecu_report(uint32_t now_ms) {
    int i;
    log_str("MON t=");
    log_u32(now_ms);
    for (i = 0; i < MON_MSGS; i++) {
        const uint8_t state = kaiwo_gateway_monitor_state(&monitor, (kaiwo_gateway_msg_t)i);
        if (state != KAIWO_GATEWAY_RX_NO_DATA) {
            log_str(" ");
            log_hex(kaiwo_gateway_msg_info((kaiwo_gateway_msg_t)i)->frame_id, 8u);
            log_str("=");
            log_u32(state);
        }
    }
    log_codes();
    log_end();
}

/* The values a message sends this cycle: the commands echoed as states, the monitor's codes. */
static void refresh(kaiwo_gateway_any_t *m) {
    switch (m->msg) {
        case KAIWO_GATEWAY_MSG_EPS_STATE:
            (void)kaiwo_gateway_eps_state_steering_angle_encode_fixed(steering_centideg, &m->u.eps_state.steering_angle);
            m->u.eps_state.counter = kaiwo_gateway_eps_state_counter_next(m->u.eps_state.counter);
            break;
        case KAIWO_GATEWAY_MSG_DRIVING_STATE: m->u.driving_state.gear_state = gear; break;
        case KAIWO_GATEWAY_MSG_VEHICLE_STATE_1:
            m->u.vehicle_state_1.counter = kaiwo_gateway_vehicle_state_1_counter_next(m->u.vehicle_state_1.counter);
            break;
        case KAIWO_GATEWAY_MSG_VEHICLE_FAULT:
            m->u.vehicle_fault.remote_entry_fault = (uint8_t)kaiwo_gateway_monitor_remote_entry_fault(&monitor);
            m->u.vehicle_fault.unmanned_entry_fault = (uint8_t)kaiwo_gateway_monitor_unmanned_entry_fault(&monitor);
            break;
        default: break;
    }
}

static void transmit_due(uint32_t now_ms) {
    size_t i;
    for (i = 0u; i < TX_COUNT; i++) {
        const kaiwo_gateway_msg_info_t *info = kaiwo_gateway_msg_info(tx_msgs[i]);
        uint8_t frame[8];
        if ((int32_t)(now_ms - tx_due[i]) < 0) {
            continue;
        }
        tx_due[i] += info->cycle_ms; /* absolute deadlines: no drift */
        refresh(&tx[i]);
        if (kaiwo_gateway_pack_any(frame, sizeof frame, &tx[i]) == KAIWO_GATEWAY_OK) {
            board_can_transmit(info->frame_id, frame, info->dlc);
        }
    }
}

void ecu_poll(uint32_t now_ms) {
    can_frame_t f;
    while (can_rx_pop(&f)) {
        receive(&f);
    }
    (void)kaiwo_gateway_monitor_check(&monitor, now_ms);
    transmit_due(now_ms);
}
