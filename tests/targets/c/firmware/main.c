/* Mock AUTOCAR controller: sends EPS commands every 20 ms with a rolling counter, receives
 * vehicle frames through the receive monitor, reassembles the VIN, reports fault codes. */
#include <stdio.h>
#include <string.h>

#include "kaiwo_gateway.h"

typedef struct {
    uint32_t id;
    uint8_t data[8];
} frame_t;

static frame_t bus[64];
static unsigned bus_len = 0;

static void can_send(uint32_t id, const uint8_t *data) {
    if (bus_len < sizeof bus / sizeof bus[0]) {
        bus[bus_len].id = id;
        memcpy(bus[bus_len].data, data, 8);
        bus_len++;
    }
}

int main(void) {
    kaiwo_gateway_autocar_eps_command_t cmd = kaiwo_gateway_autocar_eps_command_init();
    kaiwo_gateway_device_id_t dev = kaiwo_gateway_device_id_init();
    kaiwo_gateway_device_id_text_rx_t vin_rx;
    kaiwo_gateway_monitor_t mon;
    uint8_t frame[8];
    uint8_t vin_frames[KAIWO_GATEWAY_DEVICE_ID_TEXT_FRAMES][KAIWO_GATEWAY_DEVICE_ID_DLC];
    char vin[KAIWO_GATEWAY_DEVICE_ID_TEXT_LENGTH + 1u];
    uint32_t now = 0;
    unsigned i;
    int bad = 0;

    kaiwo_gateway_monitor_init(&mon);
    kaiwo_gateway_monitor_expect(&mon, KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND, now, 0u);
    cmd.eps_ctrl_mode = KAIWO_GATEWAY_EPS_MODE_CMD_AUTO_ANGLE;
    for (i = 0; i < 10u; i++, now += KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_CYCLE_MS) {
        bad |= kaiwo_gateway_autocar_eps_command_steering_angle_cmd_encode(-12.5 + (double)i, &cmd.steering_angle_cmd) != KAIWO_GATEWAY_OK;
        bad |= kaiwo_gateway_autocar_eps_command_pack(frame, sizeof frame, &cmd) != KAIWO_GATEWAY_OK;
        can_send(KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_FRAME_ID, frame);
        cmd.counter = kaiwo_gateway_autocar_eps_command_counter_next(cmd.counter);
    }
    dev.device_type = KAIWO_GATEWAY_DEVICE_TYPE_VEHICLE;
    bad |= kaiwo_gateway_device_id_text_split("LKLA6G1H8LA000205", 17u, &dev, vin_frames) != KAIWO_GATEWAY_OK;
    for (i = KAIWO_GATEWAY_DEVICE_ID_TEXT_FRAMES; i-- > 0u;) {
        can_send(KAIWO_GATEWAY_DEVICE_ID_FRAME_ID, vin_frames[i]);
    }

    kaiwo_gateway_device_id_text_rx_init(&vin_rx);
    for (i = 0, now = 0; i < bus_len; i++) {
        kaiwo_gateway_any_t rx;
        const uint32_t events = kaiwo_gateway_monitor_on_frame(&mon, bus[i].id, bus[i].data, 8u, now, &rx);
        bad |= events != 0u;
        if (rx.msg == KAIWO_GATEWAY_MSG_DEVICE_ID) {
            bad |= kaiwo_gateway_device_id_text_rx_feed(&vin_rx, bus[i].data, 8u) != KAIWO_GATEWAY_OK;
        } else {
            now += KAIWO_GATEWAY_AUTOCAR_EPS_COMMAND_CYCLE_MS;
        }
        bad |= kaiwo_gateway_monitor_check(&mon, now) != 0u;
    }
    bad |= kaiwo_gateway_device_id_text_rx_get(&vin_rx, vin, sizeof vin) != KAIWO_GATEWAY_OK;
    bad |= kaiwo_gateway_monitor_unmanned_entry_fault(&mon) != KAIWO_GATEWAY_UNMANNED_ENTRY_FAULT_NO_FAULT;
    bad |= (kaiwo_gateway_monitor_check(&mon, now + 1000u) & KAIWO_GATEWAY_RX_TIMEOUT) == 0u;
    bad |= kaiwo_gateway_monitor_unmanned_entry_fault(&mon) != KAIWO_GATEWAY_UNMANNED_ENTRY_FAULT_MESSAGE_TIMEOUT;
    printf("VIN %s, %u frames, spec %s %s\n", vin, bus_len, KAIWO_GATEWAY_SPEC_NAME, KAIWO_GATEWAY_SPEC_VERSION);
    if (bad) {
        printf("firmware FAILED\n");
        return 1;
    }
    printf("firmware ok\n");
    return 0;
}
