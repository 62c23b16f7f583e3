use super::args::DevicesArgs;
use std::process::ExitCode;
use sweeplab::vk::context::{list_devices, validation_layer_version};

pub fn run(args: &DevicesArgs) -> anyhow::Result<ExitCode> {
    let devices = list_devices()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&devices)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{:<5} {:<36} {:<15} {:<8} {:<12} {:>12} {:>10}",
        "index", "name", "type", "api", "driver", "ts period ns", "ts bits"
    );
    for d in &devices {
        println!(
            "{:<5} {:<36} {:<15} {:<8} {:<12} {:>12} {:>10}",
            d.index, d.name, d.device_type, d.api_version, d.driver_name, d.timestamp_period_ns, d.timestamp_valid_bits
        );
    }
    // Beside the devices' API versions: a layer older than a driver does not
    // know its newest extensions (tools/gpu_check.sh reports this line).
    match validation_layer_version()? {
        Some(v) => println!("validation layer: VK_LAYER_KHRONOS_validation {v}"),
        None => println!("validation layer: not installed (--validate needs vulkan-validationlayers)"),
    }
    Ok(ExitCode::SUCCESS)
}
